"""The install test's Python check: the package imports from the install prefix (argv[1]) alone
and its module works (the back ends compiled in)."""
import os
import sys

import epicycle

prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(epicycle.__file__).startswith(prefix + os.sep), epicycle.__file__
print(epicycle.__file__, epicycle.contact_backends())
