"""softimpact: multistability of oscillators coupled through soft impacts."""

__version__ = "0.1.0"
