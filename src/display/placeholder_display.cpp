// placeholder: stage display is being written
