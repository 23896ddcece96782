/*
 * The library of native kernels (quadric_contact._native): its own part.
 *
 * The kernels themselves are objects compiled from the package's Python kernels by numba at build
 * time (quadric_contact/codegen/native.py); they call numba's C runtime: the allocator of their
 * scratch arrays (NRT, numba/core/runtime/nrt.cpp, linked beside this file) and a few helper
 * functions of numba's helper library, included here from numba's sources as numba.pycc does for
 * its ahead-of-time modules.  Importing the module initialises the allocator; the kernels are then
 * called through ctypes (quadric_contact/modes/kernels/native.py), which releases the GIL.
 */
#include "_numba_common.h"
#include "_pymodule.h"

#define NUMBA_EXPORT_FUNC(_rettype) VISIBILITY_HIDDEN _rettype
#define NUMBA_EXPORT_DATA(_vartype) VISIBILITY_HIDDEN _vartype
#define PYCC_COMPILING

#include "_helperlib.c"
#include "core/runtime/nrt.h"

/* the hash secrets the helper library declares (the kernels hash nothing) */
int64_t _numba_hashsecret_siphash_k0;
int64_t _numba_hashsecret_siphash_k1;
int64_t _numba_hashsecret_djbx33a_suffix;

static int initialised = 0;

/* numba's allocator, set up once: the module's initialisation calls it, and so does a process
   that loads the library with ctypes only (the test suite runs a checkout's sources against the
   installed library) */
VISIBILITY_GLOBAL void qc_native_init(void)
{
    if (!initialised) {
        NRT_MemSys_init();
        initialised = 1;
    }
}

/* the digest of the manifest this library was linked with: a manifest that does not match (a
   library and a manifest of two builds) is not used */
VISIBILITY_GLOBAL const char *qc_native_manifest(void)
{
    return QC_MANIFEST_DIGEST;
}

static struct PyModuleDef native_module = {
    PyModuleDef_HEAD_INIT,
    "_native",
    "The package's array kernels, compiled when the package was built (see _native_manifest.json).",
    -1,
    NULL,
};

PyMODINIT_FUNC PyInit__native(void)
{
    qc_native_init();
    return PyModule_Create(&native_module);
}
