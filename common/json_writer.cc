#include "common/json_writer.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace viqu {
namespace {

std::vector<std::string> SplitDots(const std::string& key) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (parts.back().empty()) throw std::invalid_argument("JsonWriter: bad key '" + key + "'");
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

}  // namespace

JsonWriter::Value* JsonWriter::Slot(const std::string& key) {
  Value* cur = &root_;
  for (const std::string& part : SplitDots(key)) {
    if (cur->kind == Value::Kind::kNull) cur->kind = Value::Kind::kObject;
    if (cur->kind != Value::Kind::kObject) {
      throw std::logic_error("JsonWriter: '" + key + "' passes through a value that is not an object");
    }
    Value* next = nullptr;
    for (size_t i = 0; i < cur->keys.size(); ++i) {
      if (cur->keys[i] == part) next = &cur->values[i];
    }
    if (next == nullptr) {
      cur->keys.push_back(part);
      cur->values.emplace_back();
      next = &cur->values.back();
    }
    cur = next;
  }
  return cur;
}

const JsonWriter::Value* JsonWriter::Find(const std::string& key) const {
  const Value* cur = &root_;
  for (const std::string& part : SplitDots(key)) {
    if (cur->kind != Value::Kind::kObject) return nullptr;
    const Value* next = nullptr;
    for (size_t i = 0; i < cur->keys.size(); ++i) {
      if (cur->keys[i] == part) next = &cur->values[i];
    }
    if (next == nullptr) return nullptr;
    cur = next;
  }
  return cur;
}

void JsonWriter::Set(const std::string& key, double value) {
  Value v;
  v.kind = Value::Kind::kNumber;
  v.number = value;
  *Slot(key) = v;
}

void JsonWriter::Set(const std::string& key, bool value) {
  Value v;
  v.kind = Value::Kind::kBool;
  v.boolean = value;
  *Slot(key) = v;
}

void JsonWriter::Set(const std::string& key, const std::string& value) {
  Value v;
  v.kind = Value::Kind::kString;
  v.text = value;
  *Slot(key) = v;
}

void JsonWriter::Set(const std::string& key, const char* value) { Set(key, std::string(value)); }

void JsonWriter::SetSigned(const std::string& key, int64_t value) {
  Value v;
  v.kind = Value::Kind::kSigned;
  v.signed_int = value;
  *Slot(key) = v;
}

void JsonWriter::SetUnsigned(const std::string& key, uint64_t value) {
  Value v;
  v.kind = Value::Kind::kUnsigned;
  v.unsigned_int = value;
  *Slot(key) = v;
}

void JsonWriter::SetNull(const std::string& key) { *Slot(key) = Value(); }

void JsonWriter::SetNumbers(const std::string& key, const std::vector<double>& values) {
  Value array;
  array.kind = Value::Kind::kArray;
  for (double x : values) {
    Value item;
    item.kind = Value::Kind::kNumber;
    item.number = x;
    array.values.push_back(item);
  }
  *Slot(key) = array;
}

void JsonWriter::EnsureArray(const std::string& key) {
  Value* slot = Slot(key);
  if (slot->kind == Value::Kind::kNull) slot->kind = Value::Kind::kArray;
  if (slot->kind != Value::Kind::kArray) {
    throw std::logic_error("JsonWriter: '" + key + "' already holds a value that is not an array");
  }
}

void JsonWriter::Append(const std::string& key, const JsonWriter& object) {
  EnsureArray(key);
  Slot(key)->values.push_back(object.root_);
}

bool JsonWriter::Has(const std::string& key) const { return Find(key) != nullptr; }

std::string JsonWriter::FormatNumber(double value) {
  if (!std::isfinite(value)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.9g", value);
  return buf;
}

std::string JsonWriter::Quote(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);  // UTF-8 bytes pass through
        }
    }
  }
  return out + "\"";
}

void JsonWriter::Print(const Value& v, int indent, std::string* out) {
  const std::string pad(static_cast<size_t>(indent + 2), ' ');
  const std::string close_pad(static_cast<size_t>(indent), ' ');
  switch (v.kind) {
    case Value::Kind::kNull: *out += "null"; return;
    case Value::Kind::kBool: *out += v.boolean ? "true" : "false"; return;
    case Value::Kind::kNumber: *out += FormatNumber(v.number); return;
    case Value::Kind::kSigned: *out += std::to_string(v.signed_int); return;
    case Value::Kind::kUnsigned: *out += std::to_string(v.unsigned_int); return;
    case Value::Kind::kString: *out += Quote(v.text); return;
    case Value::Kind::kObject:
      if (v.keys.empty()) {
        *out += "{}";
        return;
      }
      *out += "{\n";
      for (size_t i = 0; i < v.keys.size(); ++i) {
        *out += pad + Quote(v.keys[i]) + ": ";
        Print(v.values[i], indent + 2, out);
        *out += i + 1 < v.keys.size() ? ",\n" : "\n";
      }
      *out += close_pad + "}";
      return;
    case Value::Kind::kArray:
      if (v.values.empty()) {
        *out += "[]";
        return;
      }
      *out += "[\n";
      for (size_t i = 0; i < v.values.size(); ++i) {
        *out += pad;
        Print(v.values[i], indent + 2, out);
        *out += i + 1 < v.values.size() ? ",\n" : "\n";
      }
      *out += close_pad + "]";
      return;
  }
}

std::string JsonWriter::ToString() const {
  std::string out;
  Print(root_, 0, &out);
  return out + "\n";
}

}  // namespace viqu
