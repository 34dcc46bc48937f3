// placeholder: stage render is being written
