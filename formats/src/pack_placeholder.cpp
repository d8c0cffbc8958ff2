// placeholder until the pack reader/writer land
