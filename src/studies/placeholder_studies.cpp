// placeholder: stage studies is being written
