// Text forms of evaluated values: `--dump=values` and the values quoted in diagnostics.
//
// Reals print in shortest round-trip form and always look like Reals (`2.0`, `1e+20`, `inf`); Ints as
// digits; Bool as true/false; strings quoted with \" \\ \n \t escapes; Math.Vec2/Vec3 as {x, y, z} and
// Math.Quat as {x, y, z, w}; references as `-> path`; arrays as [a, b].
#pragma once

#include <iosfwd>
#include <string>

#include "frontend/evaluation/object_graph.h"
#include "frontend/evaluation/value.h"

namespace openplx::frontend {

class Evaluator;

std::string format_real(double value);
std::string describe_value_type(const Value& value, const ObjectGraph& graph);
std::string format_value(Evaluator& evaluator, const Value& value, bool owned);

// One line per attribute of the tree under `root`, `path = value`, in declaration order; owned instances
// show their type (`rod = Rod`) and then their attributes.
void dump_values(std::ostream& out, Evaluator& evaluator, ObjectId root);

}  // namespace openplx::frontend
