// placeholder: stage analysis is being written
