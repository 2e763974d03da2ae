"""ogk software-in-the-loop harness: kernel bindings, truth models, campaigns."""
__version__ = "0.1.0"
