"""The gfbopt version (one definition; ``pyproject.toml`` reads it)."""
__version__ = "0.3.0"
