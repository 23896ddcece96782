"""Build of the native kernels (the extension ``quadric_contact._native``); everything else about
the package is in ``pyproject.toml``.

``build_ext`` runs ``python -m quadric_contact.codegen.native`` on the sources being built: numba
compiles the kernels of the default mode into objects (about a minute of CPU the first time on a
machine; its on-disk cache makes a rebuild of the same sources take seconds), and the extension
links them with numba's C runtime.  Where that fails (no C compiler, say), the build says why
and goes on without the extension: the package then compiles its kernels at run time, as
``quadric_contact.modes.kernels.native`` explains.  ``QUADRIC_CONTACT_NATIVE_BUILD=0`` skips it.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
NATIVE = "quadric_contact._native"
MANIFEST = "_native_manifest.json"


class BuildNative(build_ext):
    """``build_ext`` with the native kernels compiled first (see the module's docstring)."""

    def build_extension(self, ext: Extension) -> None:
        if ext.name != NATIVE:
            super().build_extension(ext)
            return
        if os.environ.get("QUADRIC_CONTACT_NATIVE_BUILD", "1") == "0":
            print("quadric-contact: QUADRIC_CONTACT_NATIVE_BUILD=0: no native kernels", file=sys.stderr)
            return
        work = Path(self.build_temp).resolve() / "native"
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"), env.get("PYTHONPATH")]))
        env["QUADRIC_CONTACT_NATIVE"] = "0"
        try:
            subprocess.run(
                [sys.executable, "-m", "quadric_contact.codegen.native", "--out", str(work)],
                check=True,
                env=env,
            )
            info = json.loads((work / "build.json").read_text(encoding="utf-8"))
            # the C part (numba's runtime, from numba's sources, outside this tree) compiled
            # here: the extension's own list of sources must be paths within the project
            runtime = self.compiler.compile(
                info["sources"],
                output_dir=str(work / "runtime"),
                include_dirs=info["include_dirs"],
                macros=[
                    ("PYCC_USE_NRT", "1"),
                    ("NUMBA_LAPACK_BUILD_ILP64", info["ilp64"]),
                    # the library says which manifest it was linked with (checked when loaded)
                    ("QC_MANIFEST_DIGEST", f'"{info["manifest_digest"]}"'),
                ],
                extra_preargs=["-fPIC"],
                debug=self.debug,
            )
            ext.extra_objects = [*runtime, *info["objects"]]
            ext.depends = [*ext.extra_objects, info["manifest"]]  # relink when the kernels change
            super().build_extension(ext)
            target = Path(self.get_ext_fullpath(ext.name)).parent / MANIFEST
            target.write_bytes(Path(info["manifest"]).read_bytes())
        except Exception as exc:  # a build without the native kernels still works: say so
            print(
                "quadric-contact: the native kernels were not built "
                f"({type(exc).__name__}: {exc}); the package will compile its kernels with numba "
                "at run time instead (about 40 s of CPU on first use)",
                file=sys.stderr,
            )

    def copy_extensions_to_source(self) -> None:
        """In place (``--inplace``, editable installs): the manifest goes beside the library."""
        super().copy_extensions_to_source()
        built = Path(self.build_lib) / "quadric_contact" / MANIFEST
        if built.is_file():
            package_dir = Path(self.get_finalized_command("build_py").get_package_dir("quadric_contact"))
            (package_dir / MANIFEST).write_bytes(built.read_bytes())


setup(
    ext_modules=[Extension(NATIVE, sources=[], optional=True)],
    cmdclass={"build_ext": BuildNative},
)
