// Linked into the MPI test programs of a sanitized build (TUMBLE_SANITIZE) only: a dlclose that
// unloads nothing. Open MPI loads its components (mca_*.so) with dlopen and unloads them in
// MPI_Finalize, before LeakSanitizer looks for leaks at exit; the stacks of what they allocated
// then point into unmapped memory ("<unknown module>"), which no suppression can name. Kept
// loaded, those stacks name their libraries and ensemble/openmpi.lsan.supp suppresses them.
// Defined in the executable, it is the dlclose every library of the process calls.

extern "C" int dlclose(void*) { return 0; }
