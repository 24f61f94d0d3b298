// The checks every JSON format shares, driven by its declaration
// (hb/json_schema.h, the format's XxxFields()): given a text the format's
// real writer produced, ExpectDeclarationHolds checks that
//   - reading and writing it again gives the same bytes;
//   - each declared number (and the first entry of a number list) set just
//     outside its range, or to null where null is not allowed, is refused
//     naming the field's path;
//   - an integer beyond its range, a boolean written as 0, a string outside
//     its choices, a name holding a control character, a list of fixed
//     length one entry short: each refused naming the path;
//   - each required field taken out is refused naming it;
//   - an unknown key in each object is refused naming it.
// The first instance of each field in the text is damaged (the first curve,
// the first sensor, ...); a field the text does not hold (an optional one,
// an empty list's elements) is skipped, so the sample should fill them.
#pragma once

#include <cmath>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/json_schema.h"

namespace beamid::testing {

struct SchemaCase {
  std::vector<schema::FieldDoc> fields;
  std::string sample;                                        // a text the real writer wrote
  std::function<void(const std::string& text)> read;         // throws InputError on bad input
  std::function<std::string(const std::string& text)> rewrite;  // read, then write
};

namespace schema_checks {

using Json = nlohmann::ordered_json;

// One instance of a declared path in a text: where it sits, how the reader
// names it, and its parent object.
struct Instance {
  Json* value = nullptr;
  Json* parent = nullptr;
  std::string key;   // in the parent
  std::string path;  // "curves[0].points[0].sensors.acc1.position_m"
};

inline std::vector<std::string> Tokens(const std::string& path) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t dot = path.find('.'); dot != std::string::npos; dot = path.find('.', start)) {
    out.push_back(path.substr(start, dot - start));
    start = dot + 1;
  }
  out.push_back(path.substr(start));
  return out;
}

// The first instance of a declared path ("curves[].points[].theta_rad",
// "sensors.<name>.position_m"), or none when the text does not hold one.
inline std::optional<Instance> FirstInstance(Json& root, const std::string& declared) {
  Json* at = &root;
  Instance found;
  std::string path;
  const std::vector<std::string> tokens = Tokens(declared);
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    std::string token = tokens[i];
    const bool element = token.ends_with("[]");
    if (element) token.resize(token.size() - 2);
    if (!at->is_object()) return std::nullopt;
    if (token == "<name>") {
      if (at->empty()) return std::nullopt;
      token = at->begin().key();
    }
    if (!at->contains(token)) return std::nullopt;
    found.parent = at;
    found.key = token;
    path += (path.empty() ? "" : ".") + token;
    at = &(*at)[token];
    if (element) {
      if (!at->is_array() || at->empty()) return std::nullopt;
      at = &(*at)[0];
      path += "[0]";
    }
  }
  found.value = at;
  found.path = path;
  return found;
}

// The message of the InputError that reading `text` gives, or nullopt.
inline std::optional<std::string> Refusal(const SchemaCase& c, const std::string& text) {
  try {
    c.read(text);
  } catch (const InputError& e) {
    return std::string(e.what());
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

inline void ExpectRefusedNaming(const SchemaCase& c, const Json& damaged, const std::string& path,
                                const std::string& what) {
  const std::optional<std::string> message = Refusal(c, damaged.dump(1));
  if (!message) {
    ADD_FAILURE() << what << " at \"" << path << "\" was accepted";
    return;
  }
  EXPECT_NE(message->find(path), std::string::npos) << what << ": the message does not name \"" << path << "\": "
                                                     << *message;
  EXPECT_NE(message->find("Fix:"), std::string::npos) << what << ": the message names no fix: " << *message;
}

// A number just outside the limits, or nullopt when they hold every number.
inline std::optional<double> Outside(const schema::Limits& l) {
  if (std::isfinite(l.min)) return l.min_open ? l.min : l.min - std::max(1.0, std::abs(l.min));
  if (std::isfinite(l.max)) return l.max + std::max(1.0, std::abs(l.max));
  return std::nullopt;
}

}  // namespace schema_checks

inline void ExpectDeclarationHolds(const SchemaCase& c) {
  using schema_checks::ExpectRefusedNaming;
  using schema_checks::FirstInstance;
  using schema_checks::Json;

  ASSERT_EQ(c.rewrite(c.sample), c.sample) << "the text does not survive reading and writing";
  const Json sample = Json::parse(c.sample);
  std::set<std::string> objects = {""};
  int damaged = 0;
  for (const schema::FieldDoc& f : c.fields) {
    if (f.type == "rule") continue;
    const std::size_t dot = f.path.rfind('.');
    objects.insert(dot == std::string::npos ? "" : f.path.substr(0, dot));
    Json text = sample;
    const auto instance = FirstInstance(text, f.path);
    if (!instance) continue;
    Json& v = *instance->value;
    const std::string& path = instance->path;
    const auto damage = [&](Json value, const std::string& what) {
      Json copy = sample;
      *FirstInstance(copy, f.path)->value = std::move(value);
      ExpectRefusedNaming(c, copy, path, f.path + ": " + what);
      ++damaged;
    };
    if (f.type == "number") {
      if (const auto outside = schema_checks::Outside(f.limits)) damage(*outside, "a number outside its range");
      if (!f.limits.nullable) damage(nullptr, "null where a number is required");
    } else if (f.type == "[number]" && v.is_array() && !v.empty()) {
      if (const auto outside = schema_checks::Outside(f.limits)) {
        Json list = v;
        list[0] = *outside;
        damage(list, "a list entry outside its range");
      }
    } else if (f.type == "integer") {
      damage(f.integer_max + 1, "an integer beyond its range");
      damage(1.5, "a fraction where an integer is required");
    } else if (f.type == "boolean") {
      damage(0, "0 where true or false is required");
    } else if (f.type == "string" && !f.choices.empty()) {
      damage("not-one-of-the-choices", "a string outside its choices");
    } else if (f.type == "string") {
      damage("a\x01" "b", "a control character");
    }
    if (f.count_min > 0 && v.is_array() && !v.empty()) {
      Json shorter = v;
      shorter.erase(shorter.size() - 1);
      damage(shorter, "a list of fixed length one entry short");
    }
    if (!f.optional) {
      Json copy = sample;
      const auto at = FirstInstance(copy, f.path);
      at->parent->erase(at->key);
      ExpectRefusedNaming(c, copy, path, f.path + ": a required field taken out");
      ++damaged;
    }
  }
  for (const std::string& object : objects) {
    Json copy = sample;
    Json* target = &copy;
    std::string path = "zz_not_a_field";
    if (!object.empty()) {
      const auto at = FirstInstance(copy, object);
      if (!at || !at->value->is_object()) continue;
      target = at->value;
      path = at->path + ".zz_not_a_field";
    }
    (*target)["zz_not_a_field"] = 1;
    ExpectRefusedNaming(c, copy, path, "an unknown key");
    ++damaged;
  }
  EXPECT_GT(damaged, 0) << "the sample holds none of the declared fields";
}

}  // namespace beamid::testing
