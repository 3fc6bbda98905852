"""The simulators behind `cropsight simulate <crop>`: sequence folders for examples and tests."""
from ._cropsight.simulate import broccoli

__all__ = ["broccoli"]
