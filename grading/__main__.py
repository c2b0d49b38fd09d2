from grading.cli import entry_point

entry_point()
