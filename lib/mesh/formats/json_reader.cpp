// The JSON reader of json_reader.hpp: a state machine over the text with an explicit stack of the
// open arrays and objects (RFC 8259's grammar, strictly: no comments, no trailing commas, no
// leading zeros or bare '.5'; strings must not hold raw control characters).
#include "mesh/formats/json_reader.hpp"

#include <charconv>
#include <cmath>

#include "base/errors.hpp"

namespace sculpt::mesh::detail {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// Appends code point `cp` (at most U+10FFFF) as UTF-8.
void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

/// Reads the text one token at a time; every read is bounds-checked.
class Scanner {
 public:
  Scanner(std::string_view text, const std::string& name) : text_(text), name_(name) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // a byte order mark (RFC 8259 sec. 8.1: may be ignored)
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw IoError(name_, "JSON byte " + std::to_string(pos_) + ": " + message);
  }
  /// The next character after white space, or '\0' at the end (a NUL in the text is refused as such).
  char peek() {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    if (pos_ >= text_.size()) return '\0';
    if (text_[pos_] == '\0') fail("unexpected NUL byte");
    return text_[pos_];
  }
  [[nodiscard]] bool at_end() const { return pos_ >= text_.size(); }
  void skip() { ++pos_; }

  /// A string, `pos_` at its opening quote.
  std::string string() {
    std::string out;
    ++pos_;
    for (;;) {
      if (pos_ >= text_.size()) fail("the text ends inside a string");
      const char c = text_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("a control character inside a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= text_.size()) fail("the text ends inside a string");
      switch (text_[pos_++]) {
        case '"':
          out += '"';
          break;
        case '\\':
          out += '\\';
          break;
        case '/':
          out += '/';
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          std::uint32_t cp = hex4();
          if (cp >= 0xD800 && cp < 0xDC00 && text_.substr(pos_, 2) == "\\u") {  // a surrogate pair
            const std::size_t save = pos_;
            pos_ += 2;
            const std::uint32_t low = hex4();
            if (low >= 0xDC00 && low < 0xE000)
              cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
            else
              pos_ = save;
          }
          append_utf8(out, cp >= 0xD800 && cp < 0xE000 ? 0xFFFD : cp);  // a lone surrogate: U+FFFD
          break;
        }
        default:
          --pos_;
          fail("an unknown escape in a string");
      }
    }
  }

  /// A number (RFC 8259 sec. 6 grammar), `pos_` at its first character.
  double number() {
    const std::size_t start = pos_;
    auto digits = [&] {
      const std::size_t first = pos_;
      while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
      if (pos_ == first) fail("a digit expected in a number");
    };
    if (text_[pos_] == '-') ++pos_;
    if (pos_ < text_.size() && text_[pos_] == '0')
      ++pos_;
    else
      digits();
    if (pos_ < text_.size() && text_[pos_] == '.') {
      ++pos_;
      digits();
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
      digits();
    }
    double value = 0;
    const auto [end, ec] = std::from_chars(text_.data() + start, text_.data() + pos_, value);
    if (ec != std::errc() || end != text_.data() + pos_ || !std::isfinite(value))
      fail("the number '" + std::string(text_.substr(start, pos_ - start)) + "' is out of the double range");
    return value;
  }

  /// The literal `word` (true, false, null), `pos_` at its first character.
  void literal(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) fail("an unknown word (expected a value)");
    pos_ += word.size();
  }

 private:
  std::uint32_t hex4() {
    if (text_.size() - pos_ < 4) fail("the text ends inside a \\u escape");
    std::uint32_t cp = 0;
    for (int i = 0; i < 4; ++i) {
      const char c = text_[pos_++];
      const int d = is_digit(c)              ? c - '0'
                    : (c >= 'a' && c <= 'f') ? c - 'a' + 10
                    : (c >= 'A' && c <= 'F') ? c - 'A' + 10
                                             : -1;
      if (d < 0) fail("a \\u escape needs four hexadecimal digits");
      cp = cp * 16 + static_cast<std::uint32_t>(d);
    }
    return cp;
  }

  std::string_view text_;
  const std::string& name_;
  std::size_t pos_ = 0;
};

/// What the parser expects next.
enum class Expect { Value, ValueOrClose, Key, KeyOrClose, CommaOrClose, End };

}  // namespace

JsonDocument::JsonDocument(std::string_view text, const std::string& name) {
  Scanner in(text, name);
  std::vector<std::size_t> open;  // the arrays and objects not yet closed, innermost last
  std::string key;                // the member name of the value that comes next in an object
  Expect expect = Expect::Value;
  // After a value or a closing bracket: a comma or the enclosing container's close, or the end.
  auto after_value = [&] { return open.empty() ? Expect::End : Expect::CommaOrClose; };
  auto close = [&](char c) {
    const bool object = values_[open.back()].kind == JsonKind::Object;
    if (c != (object ? '}' : ']')) in.fail(object ? "expected ',' or '}'" : "expected ',' or ']'");
    in.skip();
    open.pop_back();
    expect = after_value();
  };
  for (;;) {
    const char c = in.peek();
    switch (expect) {
      case Expect::End:
        if (!in.at_end()) in.fail("more text after the JSON value");
        return;
      case Expect::CommaOrClose:
        if (c == ',') {
          in.skip();
          expect = values_[open.back()].kind == JsonKind::Object ? Expect::Key : Expect::Value;
        } else {
          close(c);
        }
        continue;
      case Expect::KeyOrClose:
        if (c == '}') {
          close(c);
          continue;
        }
        [[fallthrough]];
      case Expect::Key:
        if (c != '"') in.fail("expected a member name in quotes");
        key = in.string();
        if (in.peek() != ':') in.fail("expected ':' after a member name");
        in.skip();
        expect = Expect::Value;
        continue;
      case Expect::ValueOrClose:
        if (c == ']') {
          close(c);
          continue;
        }
        [[fallthrough]];
      case Expect::Value: {
        const std::size_t index = values_.size();
        values_.emplace_back();
        if (!open.empty()) {
          JsonValue& parent = values_[open.back()];
          parent.children.push_back(index);
          if (parent.kind == JsonKind::Object) parent.keys.push_back(std::move(key));
        }
        JsonValue& v = values_[index];
        expect = Expect::End;  // replaced below
        switch (c) {
          case '{':
            v.kind = JsonKind::Object;
            break;
          case '[':
            v.kind = JsonKind::Array;
            break;
          case '"':
            v.kind = JsonKind::String;
            v.text = in.string();
            break;
          case 't':
            v.kind = JsonKind::Bool;
            v.boolean = true;
            in.literal("true");
            break;
          case 'f':
            v.kind = JsonKind::Bool;
            in.literal("false");
            break;
          case 'n':
            in.literal("null");
            break;
          case '\0':
            in.fail("the text ends where a value was expected");
          default:
            if (c != '-' && !is_digit(c)) in.fail(std::string("unexpected character '") + c + "' (expected a value)");
            v.kind = JsonKind::Number;
            v.number = in.number();
        }
        if (v.kind == JsonKind::Object || v.kind == JsonKind::Array) {
          in.skip();
          expect = v.kind == JsonKind::Object ? Expect::KeyOrClose : Expect::ValueOrClose;
          open.push_back(index);
        } else {
          expect = after_value();
        }
        continue;
      }
    }
  }
}

const JsonValue* JsonDocument::member(const JsonValue& object, std::string_view key) const {
  if (object.kind != JsonKind::Object) return nullptr;
  for (std::size_t i = 0; i < object.keys.size(); ++i)
    if (object.keys[i] == key) return &values_[object.children[i]];
  return nullptr;
}

}  // namespace sculpt::mesh::detail
