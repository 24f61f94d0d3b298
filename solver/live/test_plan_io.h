// The plan file `beamid watch` writes after every step, and a DAQ script (or
// `beamid simulate --serve`) polls: JSON of format "beamid-test-plan/1"
// (docs/test-plan-format.md). It is replaced atomically (written beside,
// then renamed), so a reader never sees half a plan; "sequence" grows by
// one with every plan, so a reader knows a plan it has acted on.
#pragma once

#include <filesystem>
#include <string>

#include "solver/live/test_plan.h"

namespace beamid::solver {

std::string TestPlanJson(const TestPlan& plan);
void WriteTestPlan(const std::filesystem::path& path, const TestPlan& plan);
// Throws InputError naming the file, the field and the fix.
TestPlan ParseTestPlan(const std::string& text, const std::string& source);
TestPlan ReadTestPlan(const std::filesystem::path& path);

}  // namespace beamid::solver
