"""The package version (one place: the package, its records and its tables read it)."""
__version__ = "0.2.0"
