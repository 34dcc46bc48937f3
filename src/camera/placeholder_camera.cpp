// placeholder: stage camera is being written
