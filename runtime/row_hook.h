// The process-wide mjcb_control that gives the constraint rows of every attached bridge AGX's law inside the
// user's own mj_step (MuJoCo 2.2.2 calls it after mj_fwdVelocity, before the actuation and the solve; also at
// the end of mj_step1 and in mj_forward). It dispatches by mjData, so several models and several mjData
// stepping in parallel threads each get their own rows, and it first calls the callback the program had set
// before the first attach (or set since, when it is set again while rows are attached: see
// RowHook::installed).
#pragma once

#include <mujoco/mujoco.h>

#include "runtime/constraint_rows.h"

namespace openplx::runtime {

namespace row_hook {

// Registers `rows` for `d` (several per mjData: one per bridge) and makes mjcb_control the hook.
void attach(const mjData* d, ConstraintRows* rows);
void detach(const mjData* d, ConstraintRows* rows);
// Whether mjcb_control is still the hook (a program may have replaced it after attaching).
bool installed();

}  // namespace row_hook

}  // namespace openplx::runtime
