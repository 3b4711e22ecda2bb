# module integrators: filled in by its owner
