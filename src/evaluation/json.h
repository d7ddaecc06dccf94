#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace colmap_gcn {

// A small JSON value for the benchmark's result files and caches. Numbers
// are doubles (exact for the counts we store, < 2^53); objects keep their
// keys sorted so files are deterministic. Not a general-purpose library: no
// \u escapes beyond what Dump() writes.
class JsonValue {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };

  JsonValue() = default;
  JsonValue(bool value);                // NOLINT(runtime/explicit)
  JsonValue(double value);              // NOLINT(runtime/explicit)
  JsonValue(int value);                 // NOLINT(runtime/explicit)
  JsonValue(int64_t value);             // NOLINT(runtime/explicit)
  JsonValue(uint64_t value);            // NOLINT(runtime/explicit)
  JsonValue(const char* value);         // NOLINT(runtime/explicit)
  JsonValue(const std::string& value);  // NOLINT(runtime/explicit)

  static JsonValue Array();
  static JsonValue Object();

  Type GetType() const { return type_; }
  bool IsNull() const { return type_ == Type::kNull; }

  // Typed access; throws Error on a type mismatch.
  bool AsBool() const;
  double AsDouble() const;
  int64_t AsInt() const;
  const std::string& AsString() const;
  const std::vector<JsonValue>& AsArray() const;
  const std::map<std::string, JsonValue>& AsObject() const;

  // Arrays.
  void Append(const JsonValue& value);
  size_t Size() const;

  // Objects: operator[] inserts; Get throws Error if the key is missing;
  // the Get*Or variants return the fallback for a missing key.
  JsonValue& operator[](const std::string& key);
  bool Has(const std::string& key) const;
  const JsonValue& Get(const std::string& key) const;
  double GetDoubleOr(const std::string& key, double fallback) const;
  int64_t GetIntOr(const std::string& key, int64_t fallback) const;
  std::string GetStringOr(const std::string& key,
                          const std::string& fallback) const;

  // Pretty-printed with two-space indentation when indent >= 0, one line
  // otherwise. Non-finite numbers are written as null.
  std::string Dump(int indent = 2) const;

  // Throws Error with the offset of the first problem.
  static JsonValue Parse(const std::string& text);

 private:
  void DumpTo(std::string* out, int indent, int depth) const;

  Type type_ = Type::kNull;
  bool bool_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<JsonValue> array_;
  std::map<std::string, JsonValue> object_;
};

// Reads and parses a file; throws Error naming the file.
JsonValue ReadJsonFile(const std::string& path);
// Writes atomically (see WriteFileAtomically).
void WriteJsonFile(const std::string& path, const JsonValue& value);

}  // namespace colmap_gcn
