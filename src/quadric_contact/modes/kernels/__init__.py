"""The compiled kernels: binary64 loops, their error bounds, the native library and threads."""
