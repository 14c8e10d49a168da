#pragma once
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace viqu {

// A small JSON object builder for metrics.json and `--json` outputs. Dotted keys make nested
// objects ("ate.rmse_m" -> {"ate": {"rmse_m": ...}}); keys keep their insertion order; setting a
// key again replaces its value in place. Doubles print with %.9g, NaN and infinities as null,
// integers exactly, strings escaped.
//
//   JsonWriter m;
//   m.Set("scenario", "static_room");
//   m.Set("ate.rmse_m", 0.0123);
//   JsonWriter obj;
//   obj.Set("name", "person_1");
//   m.Append("dynamic.objects", obj);
//   WriteFileAtomic(path, m.ToString());
class JsonWriter {
 public:
  void Set(const std::string& key, double value);
  void Set(const std::string& key, bool value);
  void Set(const std::string& key, const std::string& value);
  void Set(const std::string& key, const char* value);
  template <typename T, typename = std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>>>
  void Set(const std::string& key, T value) {
    if constexpr (std::is_signed_v<T>) {
      SetSigned(key, static_cast<int64_t>(value));
    } else {
      SetUnsigned(key, static_cast<uint64_t>(value));
    }
  }
  void SetNull(const std::string& key);
  // An array of numbers.
  void SetNumbers(const std::string& key, const std::vector<double>& values);
  // Appends `object` to the array at `key` (created empty on first use).
  void Append(const std::string& key, const JsonWriter& object);
  // Makes `key` an empty array if it does not exist yet (so that "no objects" prints as []).
  void EnsureArray(const std::string& key);

  bool Has(const std::string& key) const;
  // The whole object, pretty-printed with two-space indentation and a final newline.
  std::string ToString() const;

  // Number formatting used for every double: %.9g; NaN and infinities give "null".
  static std::string FormatNumber(double value);
  // A JSON string literal with quotes and escapes.
  static std::string Quote(const std::string& text);

 private:
  struct Value {
    enum class Kind { kNull, kBool, kNumber, kSigned, kUnsigned, kString, kObject, kArray };
    Kind kind = Kind::kNull;
    bool boolean = false;              // kBool
    double number = 0;                 // kNumber
    int64_t signed_int = 0;            // kSigned
    uint64_t unsigned_int = 0;         // kUnsigned
    std::string text;                  // kString
    std::vector<std::string> keys;     // kObject: member names, in order
    std::vector<Value> values;         // kObject: member values (parallel to keys); kArray: items
  };
  void SetSigned(const std::string& key, int64_t value);
  void SetUnsigned(const std::string& key, uint64_t value);
  // The value at `key`, created (null) if missing, with objects created along the path.
  Value* Slot(const std::string& key);
  const Value* Find(const std::string& key) const;
  static void Print(const Value& v, int indent, std::string* out);
  static Value ObjectValue() {
    Value v;
    v.kind = Value::Kind::kObject;
    return v;
  }

  Value root_ = ObjectValue();  // always an object
};

}  // namespace viqu
