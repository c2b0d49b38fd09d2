from validator.cli import entry_point

entry_point()
