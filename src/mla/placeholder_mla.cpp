// placeholder: stage mla is being written
