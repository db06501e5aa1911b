"""The time loop's state between two right-hand-side evaluations, as one named record.

:func:`gearcli.core.timeloop.run` keeps everything that survives from one evaluation of the
right-hand side to the next (times, step sizes, the controller's memory, the phase, the next
output row) in one record ``st`` of :data:`LOOP_DTYPE`: float64 fields (:data:`LOOP_FLOAT_NAMES`)
then int64 fields (:data:`LOOP_INT_NAMES`, flags 0/1), read and written by name (``st.h``,
``st.phase``). The phases of the loop are small functions inlined into it
(:mod:`gearcli.core.stepsize`, :mod:`gearcli.core.hops`, :mod:`gearcli.core.sampling`) that
take the record, so each can also be called, and tested, on its own (tests pass
``np.zeros(1, LOOP_DTYPE)[0]``).

In the compiled loop the record lives on run's stack (:func:`loop_state`), so LLVM keeps its
fields in registers as it kept the local variables they replace. Measured while this was
written (fine-grained A/B against the scalar loop, five cases): the state as a float64 and
an int64 vector in the work arrays, indexed by named constants, ran 1-7 % slower (every field
a load and a store that may alias K and y) and compiled slower (numba types and lowers an
array element as an indexing expression, ~3x a record field in a micro benchmark). The names
are written once here; they never leave a chunk, so they are not in layout.LAYOUT_KEY.
"""

from __future__ import annotations

import numpy as np

from gearcli.core.dopri5 import N_STAGES  # imports gearcli.core.jit: numba's cache folder

#: Float fields; times and step sizes in [s].
LOOP_FLOAT_NAMES = (
    "t",  # time of the accepted state y
    "ts",  # time of the next evaluation (stage, sample, hop end, trial)
    "t_new",  # end of the step being attempted
    "span",  # t_end - t at the start of the chunk
    "h",  # next step size
    "h_step",  # the step being attempted (cut short before a predicted crossing)
    "h_min",  # smallest step size at t (10 units in the last place of t)
    "h0",  # starting step size: trial step (HNW II.4)
    "d1",  # starting step size: scaled norm of f(t, y) [1/s]
    "factor",  # step-size factor after the last accepted step [-]
    "err_bound",  # overlap margin of a loaded crossing before the |delta| term [mm] (hops.py)
    "t_event",  # predicted next loaded table-end crossing
    "t_recheck",  # predict again before a step ends past this time
    "hop_limit",  # a crossing closer than this is hopped over
    "h_cut",  # size of the last step cut short by a crossing
    "hop",  # length of the hop in progress
    "t_hop",  # end of the hop in progress
)

#: Integer fields; flags are 0 or 1.
LOOP_INT_NAMES = (
    "phase",  # what the next evaluation is for (PH_*)
    "stage",  # stage of the step attempt, 1 .. N_STAGES (dopri5.py)
    "row",  # row of K the next evaluation writes (ROW_DY: samples and the trial)
    "full",  # the next evaluation computes the outputs too (aux, slot forces: rhs.py)
    "i_out",  # next output row
    "status",  # layout.STATUS_* once the loop stops
    "first",  # first error-controlled state component (layout.S; s1, or delta in speed mode)
    "count",  # number of controlled base components, first .. S.deltadot
    "speed_mode",  # the pinion's motion is prescribed (layout.DRIVE_SPEED)
    "fresh",  # this chunk starts the run from the initial values in prm
    "rejected_before",  # the last attempt was rejected (no growth on the next acceptance)
    "nonfinite_last",  # the last attempt produced NaN or overflow
    "cut",  # the step being attempted ends just before a predicted crossing
    "runaway",  # the last accepted step exceeded the penetration limit
    "predict",  # predict the next crossing before the next step
)
#: The record: 8 bytes a field, aligned, no padding.
LOOP_DTYPE = np.dtype([(n, np.float64) for n in LOOP_FLOAT_NAMES]
                      + [(n, np.int64) for n in LOOP_INT_NAMES], align=True)

# numba itself only now: gearcli.core.jit (imported above) sets its cache folder first
from numba import from_dtype  # noqa: E402
from numba.core import cgutils, types  # noqa: E402
from numba.extending import intrinsic  # noqa: E402

#: Its numba type (a record is passed by reference: a pointer to its bytes).
LOOP_RECORD = from_dtype(LOOP_DTYPE)

#: What the loop's one evaluation of the right-hand side is for (``st.phase``).
PH_START = 0  # f(t_start, y): K[0] of the first step
PH_FIRST_STEP = 1  # the starting step size's trial evaluation (HNW II.4)
PH_STAGE = 2  # stage s = 1 .. N_STAGES of a step attempt (the last one is FSAL, full)
PH_SAMPLE = 3  # an output row inside an accepted step (dense output)
PH_HOP_SAMPLE = 4  # an output row inside a hop over a discontinuity (Euler)
PH_HOP = 5  # f at the end of a hop: K[0] of the next step
PH_PLAN = 6  # none: decide the next step or hop

#: The row of K an evaluation writes: the stage's own (0 for f(t, y) at the start and after a
#: hop, 1 .. N_STAGES for the stages) or this scratch row (samples, the trial evaluation).
ROW_DY = N_STAGES + 1


#: The record's bytes as LLVM sees them on the stack: one double or i64 per field. numba's
#: own data type of a record is a byte array ([256 x i8]); zero-filled as that, LLVM's scalar
#: replacement split two int64 fields (stage, i_out) into eight one-byte registers each,
#: rebuilt with shifts and ors wherever they were read (bench/RESULTS.md, session 11).
#: (A numba tuple of the fields' types: its LLVM data type is that struct.)
_FIELDS = types.Tuple((types.float64,) * len(LOOP_FLOAT_NAMES)
                      + (types.int64,) * len(LOOP_INT_NAMES))


@intrinsic
def loop_state(typingctx):
    """A loop-state record (zeros) on the stack of the compiled function that calls this.

    Nothing is allocated and the record's address never leaves that function when every
    function that takes it is inlined (timeloop.run and its phases), so LLVM replaces its
    fields by registers (scalar replacement of aggregates): the named fields cost what the
    local variables they replace cost. numba's extension API (an intrinsic: the record's
    bytes as one stack slot in the entry block, numba.core.cgutils.alloca_once, zero-filled
    there, typed field by field: _FIELDS). Python callers (tests) use
    ``np.zeros(1, LOOP_DTYPE)[0]`` instead.
    """

    def codegen(context, builder, signature, args):
        slot = cgutils.alloca_once(builder, context.get_data_type(_FIELDS), name="loop_state")
        slot.align = 16  # the float64 and int64 fields are loaded as aligned
        return builder.bitcast(slot, context.get_value_type(LOOP_RECORD))

    return LOOP_RECORD(), codegen
