#include "solver/estimation/model_family.h"

#include <stdexcept>

#include "hb/errors.h"

namespace beamid::solver {

std::vector<const ModelFamily*> ModelFamilies() { return {&HarmonicBalanceFamily(), &MultipleScalesFamily()}; }

std::string ModelFamilyNames() {
  std::string names;
  for (const ModelFamily* family : ModelFamilies()) names += (names.empty() ? "" : ", ") + family->Name();
  return names;
}

const ModelFamily& FindModelFamily(const std::string& name) {
  for (const ModelFamily* family : ModelFamilies())
    if (family->Name() == name) return *family;
  std::string known;
  for (const ModelFamily* family : ModelFamilies())
    known += (known.empty() ? "" : ", ") + family->Name() + " (" + family->Description() + ")";
  throw InputError("model '" + name + "': unknown model family. Fix: use one of " + known);
}

const ModelFamily& FindModelFamily(ModelKind kind) {
  for (const ModelFamily* family : ModelFamilies())
    if (family->Kind() == kind) return *family;
  throw std::logic_error("FindModelFamily: a ModelKind without its family in ModelFamilies()");
}

}  // namespace beamid::solver
