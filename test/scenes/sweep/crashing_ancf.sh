#!/bin/sh
# Stand-in ancf for the sweep tests: a case whose scene says "crash me" dies of SIGSEGV, as a
# crashing worker would; every other case runs the real ancf ($ANCF_REAL).
if grep -q "crash me" "$2"; then kill -SEGV $$; fi
exec "$ANCF_REAL" "$@"
