#include "language/ast.hpp"

namespace sculpt::language::ast {

const char* spelling(Op op) {
  switch (op) {
    case Op::Or: return "or";
    case Op::And: return "and";
    case Op::Eq: return "==";
    case Op::Ne: return "!=";
    case Op::Lt: return "<";
    case Op::Le: return "<=";
    case Op::Gt: return ">";
    case Op::Ge: return ">=";
    case Op::Union: return "|";
    case Op::Intersect: return "&";
    case Op::Add: return "+";
    case Op::Sub: return "-";
    case Op::Mul: return "*";
    case Op::Div: return "/";
    case Op::Mod: return "%";
    case Op::Neg: return "-";
    case Op::Pos: return "+";
    case Op::Not: return "not";
  }
  return "?";
}

}  // namespace sculpt::language::ast
