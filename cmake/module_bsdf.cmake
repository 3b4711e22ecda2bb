# module bsdf: filled in by its owner
