// A SAX handler that builds the document with nlohmann's own DOM builder while keeping the key
// path of the value being read, so that a duplicate key or an overflowing number is named where
// it stands. nlohmann reports the number overflow (its out_of_range 406) through parse_error,
// with the position, which its DOM parser drops.
#include "game/scene_json.h"

#include <algorithm>
#include <set>
#include <vector>

namespace game {

namespace {

using Json = nlohmann::json;

// 1-based line and column of a byte offset.
std::string LineColumn(std::string_view text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

// A key as it stands in a path: a plain name bare, anything else quoted and escaped, so that a
// key holding a newline or a dot cannot break the message's one line or its reading.
std::string PathKey(const std::string& key) {
  const bool plain = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
  return plain ? key : Json(key).dump(-1, ' ', false, Json::error_handler_t::replace);
}

class CheckingSax {
 public:
  CheckingSax(std::string_view text, Json& root) : text_(text), dom_(root, false) {}

  bool null() { return Value() && dom_.null(); }
  bool boolean(bool v) { return Value() && dom_.boolean(v); }
  bool number_integer(Json::number_integer_t v) { return Value() && dom_.number_integer(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return Value() && dom_.number_unsigned(v); }
  bool number_float(Json::number_float_t v, const std::string& s) {
    return Value() && dom_.number_float(v, s);
  }
  bool string(std::string& v) { return Value() && dom_.string(v); }
  bool binary(Json::binary_t& v) { return Value() && dom_.binary(v); }
  bool start_object(std::size_t n) {
    const bool ok = Value() && dom_.start_object(n);
    frames_.push_back(Frame{});
    return ok;
  }
  bool key(std::string& k) {
    Frame& object = frames_.back();
    if (!object.Insert(k)) {
      const std::string where = Path(frames_.size() - 1);
      error_.message = (where.empty() ? std::string() : where + ": ") + "duplicate key " +
               Json(k).dump(-1, ' ', false, Json::error_handler_t::replace) +
               " (each key may appear once in an object)";
      return false;
    }
    object.key = k;
    object.has_key = true;
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return dom_.end_object();
  }
  bool start_array(std::size_t n) {
    const bool ok = Value() && dom_.start_array(n);
    Frame array;
    array.is_array = true;
    frames_.push_back(std::move(array));
    return ok;
  }
  bool end_array() {
    frames_.pop_back();
    return dom_.end_array();
  }
  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& ex) {
    std::string reason = ex.what();
    if (ex.id == 406) {
      // Number overflow: the position is just past the number; point at its first character.
      const std::size_t start = position >= last_token.size() ? position - last_token.size() : 0;
      const std::string path = Path(frames_.size());
      const std::string where = path.empty() ? "" : path + ": ";
      error_ = {LineColumn(text_, start),
                where + "the number " + last_token + " is too large for a double (at most about 1.8e308)"};
      return false;
    }
    // "[json.exception.parse_error.101] parse error at line 2, column 5: syntax error ...":
    // the position is given once, as LINE:COLUMN of the character at fault.
    if (const auto colon = reason.find(": "); colon != std::string::npos) reason.erase(0, colon + 2);
    error_ = {LineColumn(text_, position > 0 ? position - 1 : 0), reason};
    return false;
  }

  const JsonError& Error() const { return error_; }

 private:
  struct Frame {
    bool is_array = false;
    std::size_t index = 0;  // for arrays: one past the element being read
    bool has_key = false;   // for objects: a key has been read
    std::string key;        // the key being read
    std::vector<std::string> keys;  // the keys so far, while there are few
    std::set<std::string> many;     // the keys so far, once there are many

    // Adds a key; false when the object has it already. Scene objects hold a handful of keys,
    // where a linear search beats a set; a file with thousands in one object must not make the
    // search quadratic.
    bool Insert(const std::string& k) {
      constexpr std::size_t kFew = 32;
      if (many.empty()) {
        if (std::find(keys.begin(), keys.end(), k) != keys.end()) return false;
        keys.push_back(k);
        if (keys.size() > kFew) many.insert(keys.begin(), keys.end());
        return true;
      }
      return many.insert(k).second;
    }
  };

  // A value starts: in an array it is the next element.
  bool Value() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
    return true;
  }

  // The key path of the value being read in the first `depth` frames: "bodies[2].radius".
  std::string Path(std::size_t depth) const {
    std::string path;
    for (std::size_t i = 0; i < depth; ++i) {
      const Frame& f = frames_[i];
      if (f.is_array) {
        if (f.index > 0) path += "[" + std::to_string(f.index - 1) + "]";
      } else if (f.has_key) {
        path += (path.empty() ? "" : ".") + PathKey(f.key);
      }
    }
    return path;
  }

  std::string_view text_;
  // nlohmann's own builder (a detail type, but the one Json::parse uses), so the document is
  // exactly what Json::parse would give.
  nlohmann::detail::json_sax_dom_parser<Json> dom_;
  std::vector<Frame> frames_;
  JsonError error_;
};

}  // namespace

bool ParseJsonChecked(std::string_view text, nlohmann::json& root, JsonError& error) {
  CheckingSax sax(text, root);
  if (Json::sax_parse(text.begin(), text.end(), &sax)) return true;
  error = sax.Error();
  return false;
}

}  // namespace game
