// Sanitizer builds only (linked into every test program that opens a window: the UI tests, the
// live kiosk's start-up tests): the offscreen video driver renders through Mesa (EGL + llvmpipe), whose
// driver keeps small allocations referenced from its own globals for the life of the process.
// SDL unloads the driver when video shuts down; those blocks then lose their last reference and
// LeakSanitizer reports them from an "<unknown module>" it cannot name or suppress. Keeping shared
// objects loaded in this test program (dlclose does nothing) keeps Mesa's blocks reachable, while a
// leak in our code or SDL's is still reported.
#if defined(__SANITIZE_ADDRESS__)

extern "C" int dlclose(void*) {
  return 0;
}

#endif
