// placeholder until the spectral stage lands
