// The translation unit that builds tests/support/precompiled.h (see there).
