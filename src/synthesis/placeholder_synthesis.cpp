// placeholder: stage synthesis is being written
