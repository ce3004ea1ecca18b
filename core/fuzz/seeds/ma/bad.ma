2 1 0
v 0 0 0 1
v 1 0 0 nan
e 0 0
