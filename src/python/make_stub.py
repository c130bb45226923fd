"""Writes the stub vsil/__init__.pyi into the package folder given (run after each build)."""
import sys
from pathlib import Path

package = Path(sys.argv[1])
(package / "__init__.pyi").write_text("from typing import Any\n__version__: str\n"
                                      "def __getattr__(name: str) -> Any: ...\n")
