#include "evaluation/json.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

void DumpString(const std::string& str, std::string* out) {
  out->push_back('"');
  for (const char c : str) {
    switch (c) {
      case '"':
        *out += "\\\"";
        break;
      case '\\':
        *out += "\\\\";
        break;
      case '\n':
        *out += "\\n";
        break;
      case '\t':
        *out += "\\t";
        break;
      case '\r':
        *out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          *out += buffer;
        } else {
          out->push_back(c);
        }
    }
  }
  out->push_back('"');
}

class Parser {
 public:
  explicit Parser(const std::string& text) : text_(text) {}

  JsonValue ParseDocument() {
    JsonValue value = ParseValue();
    SkipSpace();
    if (pos_ != text_.size()) Fail("trailing characters");
    return value;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    ThrowError("invalid JSON at offset ", pos_, ": ", what);
  }

  void SkipSpace() {
    while (pos_ < text_.size() &&
           (text_[pos_] == ' ' || text_[pos_] == '\n' || text_[pos_] == '\t' ||
            text_[pos_] == '\r')) {
      ++pos_;
    }
  }

  bool Consume(const std::string& token) {
    if (text_.compare(pos_, token.size(), token) == 0) {
      pos_ += token.size();
      return true;
    }
    return false;
  }

  JsonValue ParseValue() {
    SkipSpace();
    if (pos_ >= text_.size()) Fail("unexpected end");
    const char c = text_[pos_];
    if (c == '{') return ParseObject();
    if (c == '[') return ParseArray();
    if (c == '"') return JsonValue(ParseString());
    if (Consume("true")) return JsonValue(true);
    if (Consume("false")) return JsonValue(false);
    if (Consume("null")) return JsonValue();
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    const double number = std::strtod(begin, &end);
    if (end == begin) Fail("unexpected character");
    pos_ += end - begin;
    return JsonValue(number);
  }

  std::string ParseString() {
    ++pos_;  // opening quote
    std::string str;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      char c = text_[pos_++];
      if (c == '\\') {
        if (pos_ >= text_.size()) Fail("unterminated escape");
        const char e = text_[pos_++];
        switch (e) {
          case 'n':
            c = '\n';
            break;
          case 't':
            c = '\t';
            break;
          case 'r':
            c = '\r';
            break;
          case 'u':
            if (pos_ + 4 > text_.size()) Fail("short \\u escape");
            c = static_cast<char>(
                std::strtol(text_.substr(pos_, 4).c_str(), nullptr, 16));
            pos_ += 4;
            break;
          default:
            c = e;  // \" \\ \/
        }
      }
      str.push_back(c);
    }
    if (pos_ >= text_.size()) Fail("unterminated string");
    ++pos_;
    return str;
  }

  JsonValue ParseArray() {
    ++pos_;
    JsonValue array = JsonValue::Array();
    SkipSpace();
    if (Consume("]")) return array;
    while (true) {
      array.Append(ParseValue());
      SkipSpace();
      if (Consume("]")) return array;
      if (!Consume(",")) Fail("expected , or ]");
    }
  }

  JsonValue ParseObject() {
    ++pos_;
    JsonValue object = JsonValue::Object();
    SkipSpace();
    if (Consume("}")) return object;
    while (true) {
      SkipSpace();
      if (pos_ >= text_.size() || text_[pos_] != '"') Fail("expected key");
      const std::string key = ParseString();
      SkipSpace();
      if (!Consume(":")) Fail("expected :");
      object[key] = ParseValue();
      SkipSpace();
      if (Consume("}")) return object;
      if (!Consume(",")) Fail("expected , or }");
    }
  }

  const std::string& text_;
  size_t pos_ = 0;
};

}  // namespace

JsonValue::JsonValue(bool value) : type_(Type::kBool), bool_(value) {}
JsonValue::JsonValue(double value) : type_(Type::kNumber), number_(value) {}
JsonValue::JsonValue(int value) : type_(Type::kNumber), number_(value) {}
JsonValue::JsonValue(int64_t value)
    : type_(Type::kNumber), number_(static_cast<double>(value)) {}
JsonValue::JsonValue(uint64_t value)
    : type_(Type::kNumber), number_(static_cast<double>(value)) {}
JsonValue::JsonValue(const char* value)
    : type_(Type::kString), string_(value) {}
JsonValue::JsonValue(const std::string& value)
    : type_(Type::kString), string_(value) {}

JsonValue JsonValue::Array() {
  JsonValue value;
  value.type_ = Type::kArray;
  return value;
}

JsonValue JsonValue::Object() {
  JsonValue value;
  value.type_ = Type::kObject;
  return value;
}

bool JsonValue::AsBool() const {
  if (type_ != Type::kBool) ThrowError("JSON value is not a boolean");
  return bool_;
}

double JsonValue::AsDouble() const {
  // null stands for a non-finite number (see Dump).
  if (type_ == Type::kNull) return std::nan("");
  if (type_ != Type::kNumber) ThrowError("JSON value is not a number");
  return number_;
}

int64_t JsonValue::AsInt() const {
  return static_cast<int64_t>(std::llround(AsDouble()));
}

const std::string& JsonValue::AsString() const {
  if (type_ != Type::kString) ThrowError("JSON value is not a string");
  return string_;
}

const std::vector<JsonValue>& JsonValue::AsArray() const {
  if (type_ != Type::kArray) ThrowError("JSON value is not an array");
  return array_;
}

const std::map<std::string, JsonValue>& JsonValue::AsObject() const {
  if (type_ != Type::kObject) ThrowError("JSON value is not an object");
  return object_;
}

void JsonValue::Append(const JsonValue& value) {
  if (type_ == Type::kNull) type_ = Type::kArray;
  if (type_ != Type::kArray) ThrowError("JSON value is not an array");
  array_.push_back(value);
}

size_t JsonValue::Size() const {
  return type_ == Type::kArray ? array_.size() : object_.size();
}

JsonValue& JsonValue::operator[](const std::string& key) {
  if (type_ == Type::kNull) type_ = Type::kObject;
  if (type_ != Type::kObject) ThrowError("JSON value is not an object");
  return object_[key];
}

bool JsonValue::Has(const std::string& key) const {
  return type_ == Type::kObject && object_.count(key) > 0;
}

const JsonValue& JsonValue::Get(const std::string& key) const {
  if (!Has(key)) ThrowError("JSON object has no key \"", key, "\"");
  return object_.at(key);
}

double JsonValue::GetDoubleOr(const std::string& key, double fallback) const {
  return Has(key) ? Get(key).AsDouble() : fallback;
}

int64_t JsonValue::GetIntOr(const std::string& key, int64_t fallback) const {
  return Has(key) ? Get(key).AsInt() : fallback;
}

std::string JsonValue::GetStringOr(const std::string& key,
                                   const std::string& fallback) const {
  return Has(key) ? Get(key).AsString() : fallback;
}

std::string JsonValue::Dump(int indent) const {
  std::string out;
  DumpTo(&out, indent, 0);
  if (indent >= 0) out.push_back('\n');
  return out;
}

void JsonValue::DumpTo(std::string* out, int indent, int depth) const {
  const auto newline = [&](int level) {
    if (indent < 0) return;
    out->push_back('\n');
    out->append(static_cast<size_t>(indent * level), ' ');
  };
  switch (type_) {
    case Type::kNull:
      *out += "null";
      break;
    case Type::kBool:
      *out += bool_ ? "true" : "false";
      break;
    case Type::kNumber: {
      if (!std::isfinite(number_)) {
        *out += "null";
      } else if (number_ == std::floor(number_) && std::fabs(number_) < 1e15) {
        *out += std::to_string(static_cast<int64_t>(number_));
      } else {
        char buffer[32];
        std::snprintf(buffer, sizeof(buffer), "%.17g", number_);
        *out += buffer;
      }
      break;
    }
    case Type::kString:
      DumpString(string_, out);
      break;
    case Type::kArray: {
      out->push_back('[');
      for (size_t i = 0; i < array_.size(); ++i) {
        if (i > 0) out->push_back(',');
        newline(depth + 1);
        array_[i].DumpTo(out, indent, depth + 1);
      }
      if (!array_.empty()) newline(depth);
      out->push_back(']');
      break;
    }
    case Type::kObject: {
      out->push_back('{');
      bool first = true;
      for (const auto& [key, value] : object_) {
        if (!first) out->push_back(',');
        first = false;
        newline(depth + 1);
        DumpString(key, out);
        *out += indent >= 0 ? ": " : ":";
        value.DumpTo(out, indent, depth + 1);
      }
      if (!object_.empty()) newline(depth);
      out->push_back('}');
      break;
    }
  }
}

JsonValue JsonValue::Parse(const std::string& text) {
  return Parser(text).ParseDocument();
}

JsonValue ReadJsonFile(const std::string& path) {
  try {
    return JsonValue::Parse(ReadTextFile(path));
  } catch (const Error& error) {
    ThrowError(path, ": ", error.what());
  }
}

void WriteJsonFile(const std::string& path, const JsonValue& value) {
  WriteFileAtomically(path, value.Dump());
}

}  // namespace colmap_gcn
