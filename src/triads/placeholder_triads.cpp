// placeholder: stage triads is being written
