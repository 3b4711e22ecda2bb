# module loader: filled in by its owner
