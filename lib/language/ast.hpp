#pragma once
/// \file ast.hpp
/// The syntax tree of a sculpt script, produced by the parser (grammar.cpp) and walked by the
/// interpreter (interpreter.cpp). Plain Boost.Variant types: no Spirit X3 header is needed to
/// read or walk a tree. Every node records `where`, the byte offset of its first character in
/// the source text, from which errors compute `file:line:col`.
///
/// Binary operators are stored flat, one `Expression` per precedence level that has operators
/// (first operand and a list of (operator, operand) pairs; levels without operators are left
/// out), prefix operators as a list: a long chain such as `1+1+...+1` or `- - - x` is a loop,
/// not a deep tree. Only brackets nest, and the parser limits their depth (kMaxNesting in
/// parser.hpp).

#include <boost/optional.hpp>
#include <boost/variant.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace sculpt::language::ast {

/// Base of every node that carries a source position.
struct Node {
  std::size_t where = 0;
};

enum class Op {
  Or, And,                     // logical, short-circuit
  Eq, Ne, Lt, Le, Gt, Ge,      // comparison
  Union, Intersect,            // | and & (solids)
  Add, Sub, Mul, Div, Mod,     // arithmetic (- is also solid difference)
  Neg, Pos, Not                // prefix
};

/// The operator as written in scripts ("+", "and", ...).
const char* spelling(Op op);

struct Nil : Node {};
struct Identifier : Node {
  std::string name;
};
struct NumberLiteral : Node {
  double value = 0;
};
struct StringLiteral : Node {
  std::string value;
};
struct BoolLiteral : Node {
  bool value = false;
};

struct ListLiteral;
struct Expression;
struct Prefixed;
struct Postfix;

using Operand = boost::variant<Nil, NumberLiteral, StringLiteral, BoolLiteral, Identifier,
                               boost::recursive_wrapper<ListLiteral>,
                               boost::recursive_wrapper<Expression>,
                               boost::recursive_wrapper<Prefixed>,
                               boost::recursive_wrapper<Postfix>>;

/// One `op operand` step of a precedence level.
struct Operation : Node {
  Op op = Op::Add;
  Operand operand;
};

/// `first op1 x1 op2 x2 ...`, all operators of one precedence level, evaluated left to right.
struct Expression : Node {
  Operand first;
  std::vector<Operation> rest;
};

/// `[a, b, c]`
struct ListLiteral : Node {
  std::vector<Expression> items;
};

/// `name = value` inside a call's argument list, or a positional value when `name` is empty.
struct Argument : Node {
  boost::optional<Identifier> name;
  Expression value;
};

/// `(args...)` after an operand.
struct CallArguments : Node {
  std::vector<Argument> arguments;
};
/// `[index]` after an operand, or a slice `[start:stop]` (either bound may be left out).
struct Subscript : Node {
  Expression index;  ///< [index]; unused by a slice
  bool slice = false;
  boost::optional<Expression> start;
  boost::optional<Expression> stop;
};
/// The `:stop` of a slice (grammar only).
struct SliceTail : Node {
  boost::optional<Expression> stop;
};
using PostfixOp = boost::variant<CallArguments, Subscript>;

/// `primary(args)[i]...`
struct Postfix : Node {
  Operand primary;
  std::vector<PostfixOp> ops;
};

/// Prefix operators applied right to left: signs (`- + x`), or `not` (its own, looser level).
struct Prefixed : Node {
  std::vector<Op> ops;
  Operand operand;
};

// ---- statements ----

struct Block;
struct If;
struct For;
struct FunctionDefinition;

struct Assignment : Node {
  Identifier target;
  Expression value;
};
struct Return : Node {
  boost::optional<Expression> value;
};
struct Include : Node {
  StringLiteral path;
};

using Statement = boost::variant<Expression, Assignment, Return, Include,
                                 boost::recursive_wrapper<If>, boost::recursive_wrapper<For>,
                                 boost::recursive_wrapper<FunctionDefinition>>;

struct Block : Node {
  std::vector<Statement> statements;
};

/// `if condition { ... }` and each `else if condition { ... }`.
struct ConditionalBlock : Node {
  Expression condition;
  Block body;
};

/// `if c1 {..} else if c2 {..} ... else {..}`, stored flat.
struct If : Node {
  std::vector<ConditionalBlock> branches;
  boost::optional<Block> otherwise;
};

struct For : Node {
  Identifier variable;
  Expression sequence;
  Block body;
};

struct FunctionDefinition : Node {
  Identifier name;
  std::vector<Identifier> parameters;
  Block body;
};

struct Program : Node {
  std::vector<Statement> statements;
};

}  // namespace sculpt::language::ast
