import sys
from pathlib import Path

# The emulator from the source tree.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
