// placeholder: stage view is being written
