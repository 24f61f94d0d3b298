#include "solver/estimation/model_family.h"

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

const ModelFamily& FindModelFamily(ModelKind kind) { return FindModelFamily(std::string(schema::NameOf(kind, kModelKindNames))); }

}  // namespace beamid::solver
