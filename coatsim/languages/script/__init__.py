"""What the robot languages share: for the statement languages (RAPID, KRL) a tokenizer and an
expression parser configured per language, their syntax nodes and control flow; for the readers
that carry them as values (URScript, G-code, Fanuc TP) the unknowns a program reads but never sets;
and the rules of names and comment text several languages use. Each language keeps its own
statements, semantics and interpreter."""
