"""What the statement languages (RAPID, KRL) share: a tokenizer and an expression parser
configured per language, and their syntax nodes. Each language keeps its own statements,
semantics and interpreter."""
