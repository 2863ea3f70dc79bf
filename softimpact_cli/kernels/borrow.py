"""Borrowed arrays: an array's view without reference counting, for the step loops.

numba counts references to every array a jitted function binds to a name: each argument
bound by an inlined hook, each row view ``work[K0 + s]`` handed to the right-hand side,
each array passed to a call that is not inlined costs an ``NRT_incref`` and an
``NRT_decref``, an atomic add on the array's memory info each (and a call). The adaptive
loop binds a dozen arrays per step, ~6 views per step go to the right-hand side, and that
counting cost ~60 ns per dopri5 step on a 4-variable system (measured, issue 15: a sixth
of the step; more than the step's error estimate and dense output together).

``borrow(a)`` is ``a`` with a null memory info: the same data, shape and strides, and every
reference-count operation on it (or on a view of it) is a null test. It is safe exactly
while someone else holds a counted reference to ``a`` for as long as the borrowed array is
used, and the borrowed array does not escape (is not returned or stored): the loops
borrow their own arguments, which their caller holds for the whole call, and use the
borrowed arrays inside the call only. Never borrow an array created in the same function
(its only counted reference dies at its last use, and the borrowed one would dangle).
"""

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic


@intrinsic
def borrow(typingctx, arr):
    """``arr`` without reference counting (see the module's doc); the same type."""
    if not isinstance(arr, types.Array):
        return None

    def codegen(context, builder, signature, args):
        ary = context.make_array(arr)(context, builder, args[0])
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        return ary._getvalue()

    return arr(arr), codegen
