// placeholder: stage scene is being written
