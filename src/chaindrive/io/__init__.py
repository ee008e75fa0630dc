"""Reading and writing design files."""
