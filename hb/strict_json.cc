#include "hb/strict_json.h"

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "hb/errors.h"

namespace beamid {
namespace {

// Builds the document from nlohmann's SAX events (as its own DOM parser
// does), refusing what ParseStrictJson refuses at the event that shows it.
template <typename Json>
class StrictSax {
 public:
  using number_integer_t = typename Json::number_integer_t;
  using number_unsigned_t = typename Json::number_unsigned_t;
  using number_float_t = typename Json::number_float_t;
  using string_t = typename Json::string_t;
  using binary_t = typename Json::binary_t;

  // What was refused, and the fix, or nothing.
  struct Refusal {
    std::string problem;
    std::string fix;
  };

  StrictSax(Json& root, const StrictJsonLimits& limits) : root_(root), limits_(limits) {}

  bool null() { return Place(Json(nullptr)) != nullptr; }
  bool boolean(bool v) { return Place(Json(v)) != nullptr; }
  bool number_integer(number_integer_t v) { return Place(Json(v)) != nullptr; }
  bool number_unsigned(number_unsigned_t v) { return Place(Json(v)) != nullptr; }
  bool number_float(number_float_t v, const string_t& text) {
    // Kept should the parser ever hand ±inf on (JSON has no infinity).
    if (!std::isfinite(v))
      return Refuse("not valid JSON (the number " + text + At(ChildPath()) +
                        " is out of range: a double holds at most ±1.8e308)",
                    "write a finite number in SI units");
    return Place(Json(v)) != nullptr;
  }
  bool string(string_t& v) { return Place(Json(std::move(v))) != nullptr; }
  bool binary(binary_t&) { return Refuse("holds binary data", "give a JSON text"); }

  bool start_object(std::size_t) { return Open(Json::object()); }
  bool start_array(std::size_t) { return Open(Json::array()); }
  bool end_object() { return Close(); }
  bool end_array() { return Close(); }

  bool key(string_t& k) {
    Frame& frame = stack_.back();
    frame.key = std::move(k);
    if (frame.value->contains(frame.key))
      return Refuse("the key \"" + frame.key + "\" is written twice in one object" + At(ChildPath()) +
                        "; a reader would silently take one of the two values",
                    "keep one of the two entries");
    if (frame.value->size() >= limits_.max_object_members)
      return Refuse("an object holds more than " + std::to_string(limits_.max_object_members) + " keys" +
                        At(frame.path),
                    "give a file of the format (no beamid file has objects that large)");
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token, const nlohmann::detail::exception& e) {
    // nlohmann's parser finds a number beyond double's range itself (its
    // out_of_range 406, with neither line nor path): name both.
    if (e.id == 406)
      return Refuse("not valid JSON (the number " + last_token + At(ChildPath()) + " ending at byte " +
                        std::to_string(position) + " is out of range: a double holds at most ±1.8e308)",
                    "write a finite number in SI units");
    // "[json.exception.parse_error.101] parse error at line 3, column 14: syntax error ..."
    std::string what = e.what();
    if (const auto bracket = what.find("] "); what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos)
      what.erase(0, bracket + 2);
    refusal_ = Refusal{"not valid JSON (" + what + ")", "correct the JSON at that line and column"};
    return false;
  }

  const std::optional<Refusal>& refusal() const { return refusal_; }

 private:
  struct Frame {
    Json* value;       // the open object or array
    std::string path;  // its path, "" for the root
    std::string key;   // an object's key whose value comes next
  };

  static std::string At(const std::string& path) { return path.empty() ? "" : " (at \"" + path + "\")"; }

  // The path of the value that comes next.
  std::string ChildPath() const {
    if (stack_.empty()) return "";
    const Frame& frame = stack_.back();
    if (frame.value->is_array()) return frame.path + "[" + std::to_string(frame.value->size()) + "]";
    return frame.path.empty() ? frame.key : frame.path + "." + frame.key;
  }

  bool Refuse(std::string problem, std::string fix) {
    if (!refusal_) refusal_ = Refusal{std::move(problem), std::move(fix)};
    return false;
  }

  // Puts the next value where it belongs; nullptr once refused.
  Json* Place(Json&& value) {
    if (++values_ > limits_.max_values) {
      Refuse("holds more than " + std::to_string(limits_.max_values) + " JSON values" + At(ChildPath()),
             "give a file of the format (no beamid file is that large)");
      return nullptr;
    }
    if (stack_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Frame& frame = stack_.back();
    if (frame.value->is_array()) {
      frame.value->push_back(std::move(value));
      return &frame.value->back();
    }
    Json& slot = (*frame.value)[frame.key];
    slot = std::move(value);
    return &slot;
  }

  bool Open(Json&& container) {
    std::string path = ChildPath();
    if (stack_.size() >= static_cast<std::size_t>(limits_.max_depth))
      return Refuse("nests objects and arrays deeper than " + std::to_string(limits_.max_depth) + " levels" +
                        At(path),
                    "give a file of the format (no beamid file nests that deep)");
    Json* placed = Place(std::move(container));
    if (placed == nullptr) return false;
    // Pointers into the parents stay valid: a parent grows only after its
    // open child is closed.
    stack_.push_back(Frame{placed, std::move(path), {}});
    return true;
  }

  bool Close() {
    stack_.pop_back();
    return true;
  }

  Json& root_;
  const StrictJsonLimits& limits_;
  std::vector<Frame> stack_;
  std::size_t values_ = 0;
  std::optional<Refusal> refusal_;
};

}  // namespace

template <typename Json>
Json ParseStrictJson(std::string_view text, const std::string& source, std::string_view format_doc,
                     const StrictJsonLimits& limits) {
  Json root;
  StrictSax<Json> sax(root, limits);
  const bool parsed = Json::sax_parse(text.begin(), text.end(), &sax, nlohmann::json::input_format_t::json,
                                      /*strict=*/true, /*ignore_comments=*/false);
  if (!parsed || sax.refusal()) {
    const auto refusal =
        sax.refusal().value_or(typename StrictSax<Json>::Refusal{"not valid JSON", "correct the JSON"});
    std::string fix = refusal.fix;
    if (!format_doc.empty()) fix += " (" + std::string(format_doc) + ")";
    throw InputError(source, "", refusal.problem, fix);
  }
  return root;
}

template nlohmann::ordered_json ParseStrictJson<nlohmann::ordered_json>(std::string_view, const std::string&,
                                                                        std::string_view, const StrictJsonLimits&);
template nlohmann::json ParseStrictJson<nlohmann::json>(std::string_view, const std::string&, std::string_view,
                                                        const StrictJsonLimits&);

}  // namespace beamid
