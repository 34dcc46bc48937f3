// placeholder: stage rays is being written
