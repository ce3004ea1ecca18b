# capsule
2 1 0
v 0 0 0 1
v 4 0 0 0.5
e 0 1
