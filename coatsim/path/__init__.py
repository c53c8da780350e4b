"""Language-neutral program core: the plan of a program, placed paths, the tool path a program
makes the robot execute, and conversions between them."""
