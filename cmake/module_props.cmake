# module props: filled in by its owner
