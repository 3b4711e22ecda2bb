# module light: filled in by its owner
