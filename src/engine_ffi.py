"""Writes the engine's interface for Python from the public header, at build time:

- the cffi module (out-of-line ABI mode): `ffi` with every declaration already compiled into
  tables, so importing syssimx parses no C, and INTERFACE_DIGEST, the header's SHA-256;
- a C file defining ssx_interface_digest() with the same digest, linked into the library, so
  that a library and a module built from different headers are refused when the library is
  opened instead of calling functions with the wrong signature.

Usage: engine_ffi.py syssimx_engine.h OUTPUT_MODULE.py OUTPUT_SOURCE.c
"""

import hashlib
import sys

from cffi import FFI

from version_script import declarations

MODULE = "syssimx._engine_ffi"


def main(header: str, module_path: str, source_path: str) -> None:
    with open(header, "rb") as source:
        digest = hashlib.sha256(source.read()).hexdigest()
    builder = FFI()
    builder.cdef(declarations(header))
    builder.set_source(MODULE, None)
    builder.emit_python_code(module_path)
    with open(module_path, "a", encoding="utf-8") as module:
        module.write(f"\nINTERFACE_DIGEST = {digest!r}\n")
    with open(source_path, "w", encoding="utf-8") as source:
        source.write('#include "syssimx_engine.h"\n\n'
                     f'const char *ssx_interface_digest(void) {{ return "{digest}"; }}\n')


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3])
