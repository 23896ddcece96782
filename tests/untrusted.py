"""An audit hook that fails a test when untrusted text reaches anything but the parser.

``with untrusted(): ...`` arms a :func:`sys.addaudithook` hook for the block.
While armed, the hook *blocks* (raises :class:`PermissionError` from the
audited call, so nothing runs) and records:

* running a program: ``os.system``, ``subprocess.Popen``, ``os.exec*``,
  ``os.posix_spawn``, ``os.spawn*``, ``os.fork``, ``pty.spawn``;
* compiling or executing code that is not a module read from a file (``eval``,
  ``exec``, ``compile`` of text: what ``sympify`` and ``parse_expr`` do);
* creating or changing files: ``open`` for writing, ``os.mkdir``,
  ``os.rename``, ``os.remove``, ``shutil.*``, ...;
* loading native code and opening sockets.

A recorded event fails the block with an :class:`AssertionError`, even if the
code under test caught the :class:`PermissionError`.  An audit hook cannot be
removed, so it is installed once, on import, and does nothing while disarmed.
Code must be warmed up before it runs armed: a first import of a module executes
its code (allowed: it comes from a file) and may build classes with ``exec``
of generated text (``dataclasses``, ``namedtuple``), which is refused.

It also holds the hostile corpus that the tests send through every entry point.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Iterator
from typing import Any, ClassVar

_RUN = {
    "os.system",
    "subprocess.Popen",
    "os.exec",
    "os.posix_spawn",
    "os.spawn",
    "os.fork",
    "os.forkpty",
    "os.startfile",
    "pty.spawn",
    "os.kill",
    "os.killpg",
}
_FILES = {
    "os.mkdir",
    "os.rename",
    "os.replace",
    "os.remove",
    "os.rmdir",
    "os.symlink",
    "os.link",
    "os.truncate",
    "os.chmod",
    "os.chown",
    "os.utime",
    "shutil.copyfile",
    "shutil.copymode",
    "shutil.copystat",
    "shutil.copytree",
    "shutil.move",
    "shutil.rmtree",
    "shutil.make_archive",
    "shutil.unpack_archive",
}
_OTHER = {"ctypes.dlopen", "ctypes.dlsym", "ctypes.call_function", "socket.connect", "socket.bind", "import"}
_WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_TRUNC


class _State:
    armed = False
    inside = False
    violations: ClassVar[list[str]] = []


def _from_file(name: Any) -> bool:
    return isinstance(name, str) and not name.startswith("<") and os.path.isfile(name)


def _judge(event: str, args: tuple[Any, ...]) -> str | None:
    if event in _RUN or event in _FILES:
        return f"{event}{args!r:.200}"
    if event == "import":
        # importing a module that was never imported: its code runs (allowed,
        # it is a file) but a module named by untrusted text is not
        name = args[0] if args else ""
        return None if name in sys.modules else f"import of {name!r} (never imported before)"
    if event in _OTHER:
        return f"{event}{args!r:.200}"
    if event == "exec":
        code = args[0] if args else None
        filename = getattr(code, "co_filename", None)
        return None if _from_file(filename) else f"exec of code from {filename!r}"
    if event == "compile":
        source, filename = (*args, None, None)[:2]
        if _from_file(filename if not isinstance(filename, bytes) else filename.decode(errors="replace")):
            return None
        return f"compile of {source!r:.200} ({filename!r})"
    if event == "open":
        path, mode, flags = (*args, None, None, None)[:3]
        if isinstance(mode, str) and set(mode) & set("wax+"):
            return f"open({path!r}, {mode!r})"
        if mode is None and isinstance(flags, int) and flags & _WRITE_FLAGS:
            return f"open({path!r}, flags={flags:#o})"
    return None


def _hook(event: str, args: tuple[Any, ...]) -> None:
    if not _State.armed or _State.inside:
        return
    _State.inside = True
    try:
        problem = _judge(event, args)
    finally:
        _State.inside = False
    if problem is not None:
        _State.violations.append(problem)
        raise PermissionError(f"blocked while reading untrusted input: {problem}")


sys.addaudithook(_hook)


@contextlib.contextmanager
def untrusted() -> Iterator[list[str]]:
    """Arm the hook for the block; fail it (AssertionError) if anything was recorded."""
    if _State.armed:  # nested: the outer block judges
        yield _State.violations
        return
    _State.violations = []
    _State.armed = True
    try:
        yield _State.violations
    finally:
        _State.armed = False
        if _State.violations:
            raise AssertionError(f"untrusted input reached: {_State.violations}")


# -- the hostile corpus ----------------------------------------------------------------------


def _wrap_close_index() -> int:
    return next(i for i, c in enumerate(object.__subclasses__()) if c.__name__ == "_wrap_close")


PAYLOAD = (
    f"().__class__.__base__.__subclasses__()[{_wrap_close_index()}].__init__.__globals__['system']"
    "('touch PWNED')"
)
"""The issue's example: ``os.system`` reached through ``os._wrap_close``, no name needed."""

HOSTILE: tuple[str, ...] = (
    PAYLOAD,
    "().__class__.__base__.__subclasses__()",
    "exec('import os; os.system(\"touch PWNED\")')",
    'eval(\'__import__("os").system("touch PWNED")\')',
    "__import__('os').system('touch PWNED')",
    "__import__('subprocess').Popen(['touch', 'PWNED'])",
    "open('PWNED', 'w')",
    "compile('1', 'PWNED', 'eval')",
    "x.__class__.__mro__",
    "getattr(x, '__class__')",
    "(lambda: __import__('os'))()",
    "lambda x: x",
    "[c for c in ().__class__.__bases__]",
    "{c for c in range(9)}",
    "(c for c in range(9))",
    "x if y else z",
    "(x := 1)",
    "x**2 + 9**9**9",
    "x**2 - 10**10**10",
    "9**9**9**9",
    "2**99999999",
    "x**99999999",
    "1e99999999",
    "1e-99999999 + x",
    "1" * 100_000,
    "x" * 100_000,
    "x + " * 30_000 + "1",
    "(" * 100_000 + "x" + ")" * 100_000,
    "-" * 100_000 + "x",
    "(" * 80 + "x" + ")" * 80,
    "((((x",
    "x\x00",
    "\x00",
    "x\x1b[2J",
    "x\r\ny",
    "Symbol('x')",
    "Integer(1)/0",
    "sympify('x')",
    "S('x')",
    "Rational(1, 3)",
    "Float('inf')",
    "sqrt(-1)",
    "I",
    "oo",
    "zoo",
    "globals()",
    "__builtins__",
    "breakpoint()",
    "input()",
    "x@y",
    "x; import os",
    "`touch PWNED`",
    "$(touch PWNED)",
    "${7*7}",
    "{{7*7}}",
    "%s%s%s%n",
    "\uff58**2",
    "\U0001d465**2",
    "x\u200b + 1",
    "\u202ex",
    "\u0663*x",
    "0x1F",
    "0b101",
    "1j",
    "1_",
    "x2 + y2 + z2 - 1",
    "sin(x)",
    "3(z - 1)",
)
"""Every string here is refused by every entry point (none is a valid equation or number)."""
