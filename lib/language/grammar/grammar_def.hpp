#pragma once
/// \file grammar_def.hpp
/// The sculpt grammar (docs/language.md "Syntax"). Grammar-only header.
///
/// Statements end at a newline or ';'. The skipper skips blanks and `#` comments but not
/// newlines; newlines are allowed explicitly (`lb`) after an opening bracket, a comma, a binary
/// operator and before a closing bracket. `>` marks the points where the parser has committed:
/// a failure after one is reported as "expected X here".

#include <boost/spirit/home/x3.hpp>

#include <cstdlib>
#include <string>

#include "language/ast.hpp"
#include "language/grammar/ast_adapted.hpp"
#include "language/grammar/config.hpp"
#include "language/grammar/error_handler.hpp"
#include "language/grammar/grammar.hpp"

namespace sculpt::language::grammar {
namespace x3 = boost::spirit::x3;
// Character classes in the ASCII encoding: names and numbers are ASCII, and its ischar refuses
// a byte >= 128 before classifying it (the standard encoding would pass a negative char to
// std::isalnum, undefined behaviour; Boost asserts on it).
using ast::Op;
using x3::char_;
using x3::eoi;
using x3::eol;
using x3::lexeme;
using x3::lit;
using x3::ascii::alnum;
using x3::ascii::alpha;

/// Unsigned decimals (`-` is an operator; `nan` and `inf` are names): digits with an optional
/// fraction and exponent, or a fraction alone (`.5`). The text is converted by strtod, so a
/// literal too large for a double becomes infinity and the interpreter reports it (a real
/// parser would just fail here, and the message would be a puzzling "expected expression").
const auto digits = +x3::ascii::digit;
const auto number_text = x3::raw[lexeme[((digits >> -(lit('.') >> *x3::ascii::digit)) | (lit('.') >> digits)) >>
                                        -(x3::no_case[lit('e')] >> -(lit('+') | lit('-')) >> digits)]];
const auto to_double = [](auto& context) {
  const auto& range = x3::_attr(context);
  const std::string text(range.begin(), range.end());
  x3::_val(context).value = std::strtod(text.c_str(), nullptr);
};

// ---- rule IDs: each tags its node with a source position ----
struct identifier_class : annotate_position {};
struct number_class : annotate_position {};
struct string_class : annotate_position {};
struct bool_class : annotate_position {};
struct list_class : annotate_position {};
struct paren_class : annotate_position {};
struct primary_class : annotate_position {};
struct argument_class : annotate_position {};
struct named_argument_class : annotate_position {};
struct positional_argument_class : annotate_position {};
struct call_class : annotate_position {};
struct subscript_class : annotate_position {};
struct subscript_body_class : annotate_position {};
struct index_or_slice_class : annotate_position {};
struct slice_from_start_class : annotate_position {};
struct slice_tail_class : annotate_position {};
struct postfix_class : annotate_position {};
struct prefix_op_class : annotate_position {};
struct prefixed_class : annotate_position {};
struct multiplicative_operation_class : annotate_position {};
struct additive_operation_class : annotate_position {};
struct intersect_operation_class : annotate_position {};
struct union_operation_class : annotate_position {};
struct compare_operation_class : annotate_position {};
struct and_operation_class : annotate_position {};
struct or_operation_class : annotate_position {};
struct multiplicative_class : annotate_position {};
struct additive_class : annotate_position {};
struct intersect_class : annotate_position {};
struct union_class : annotate_position {};
struct compare_class : annotate_position {};
struct and_class : annotate_position {};
struct negation_class : annotate_position {};
struct expression_class : annotate_position {};
struct assignment_class : annotate_position {};
struct return_class : annotate_position {};
struct include_class : annotate_position {};
struct block_class : annotate_position {};
struct conditional_class : annotate_position {};
struct if_class : annotate_position {};
struct for_class : annotate_position {};
struct function_class : annotate_position {};
struct statement_class : annotate_position {};
struct program_class : annotate_position {};
struct end_of_statement_class;
struct end_of_input_class;
struct escape_class;
struct keyword_in_class;
struct close_brace_class;
struct not_element_assignment_class;

const x3::rule<identifier_class, ast::Identifier> identifier = "name";
const x3::rule<number_class, ast::NumberLiteral> number = "number";
const x3::rule<string_class, ast::StringLiteral> string = "string";
const x3::rule<escape_class, char> escape = "escape sequence (\\n, \\t, \\\\ or \\\")";
const x3::rule<bool_class, ast::BoolLiteral> boolean = "true or false";
const x3::rule<list_class, ast::ListLiteral> list = "list";
const x3::rule<paren_class, ast::Expression> parenthesized = "parenthesized expression";
const x3::rule<primary_class, ast::Operand> primary = "value";
const x3::rule<argument_class, ast::Argument> argument = "argument";
const x3::rule<named_argument_class, ast::Argument> named_argument = "argument";
const x3::rule<positional_argument_class, ast::Argument> positional_argument = "argument";
const x3::rule<call_class, ast::CallArguments> call = "call";
const x3::rule<subscript_class, ast::Subscript> subscript = "subscript";
const x3::rule<subscript_body_class, ast::Subscript> subscript_body = "expression";
const x3::rule<index_or_slice_class, ast::Subscript> index_or_slice = "expression";
const x3::rule<slice_from_start_class, ast::Subscript> slice_from_start = "expression";
const x3::rule<slice_tail_class, ast::SliceTail> slice_tail = "':'";
const x3::rule<postfix_class, ast::Operand> postfix = "value";
const x3::rule<prefix_op_class, ast::Op> prefix_op = "prefix operator";
const x3::rule<prefixed_class, ast::Operand> prefixed = "expression";
// One rule per level for `operator operand`, so that each Operation records the operator's position.
const x3::rule<multiplicative_operation_class, ast::Operation> multiplicative_operation = "operation";
const x3::rule<additive_operation_class, ast::Operation> additive_operation = "operation";
const x3::rule<intersect_operation_class, ast::Operation> intersect_operation = "operation";
const x3::rule<union_operation_class, ast::Operation> union_operation = "operation";
const x3::rule<compare_operation_class, ast::Operation> compare_operation = "operation";
const x3::rule<and_operation_class, ast::Operation> and_operation = "operation";
const x3::rule<or_operation_class, ast::Operation> or_operation = "operation";
const x3::rule<multiplicative_class, ast::Operand> multiplicative = "expression";
const x3::rule<additive_class, ast::Operand> additive = "expression";
const x3::rule<intersect_class, ast::Operand> intersection = "expression";
const x3::rule<union_class, ast::Operand> union_ = "expression";
const x3::rule<compare_class, ast::Operand> comparison = "expression";
const x3::rule<negation_class, ast::Operand> negation = "expression";
const x3::rule<and_class, ast::Operand> conjunction = "expression";
const x3::rule<expression_class, ast::Expression> expression = "expression";
const x3::rule<assignment_class, ast::Assignment> assignment = "assignment";
const x3::rule<return_class, ast::Return> return_statement = "return";
const x3::rule<include_class, ast::Include> include_statement = "include";
const x3::rule<block_class, ast::Block> block = "'{'";
const x3::rule<conditional_class, ast::ConditionalBlock> conditional = "condition";
const x3::rule<if_class, ast::If> if_statement = "if";
const x3::rule<for_class, ast::For> for_statement = "for";
const x3::rule<function_class, ast::FunctionDefinition> function_definition = "fn";
const x3::rule<statement_class, ast::Statement> statement = "statement";
const x3::rule<end_of_statement_class> end_of_statement = "newline or ';'";
const x3::rule<end_of_input_class> end_of_input = "statement";
const x3::rule<keyword_in_class> keyword_in = "'in'";
const x3::rule<close_brace_class> close_brace = "'}'";
/// Named for grammar.cpp, which words the message (kElementAssignment in parser.hpp).
const x3::rule<not_element_assignment_class> not_element_assignment = "element assignment";
const skipper_type skipper = "whitespace";
const program_type program = "program";

/// Semantic action that moves the parsed attribute into one member of the rule's node
/// (used for one-member nodes, which X3 1.74 does not fill from a sequence by itself).
/// A rule whose right side holds an action gets no on_success call with its node (X3 passes
/// `unused`), so such rules start with `mark`, which records where the node starts (after
/// skipping blanks: eps skips before it matches).
const auto mark = x3::eps[([](auto& context) {
  const PositionTracker& tracker = x3::get<position_tag>(context).get();
  x3::_val(context).where = static_cast<std::size_t>(x3::_where(context).begin() - tracker.begin);
})];

template <typename Node, typename Member>
auto into(Member Node::*member) {
  return [member](auto& context) { x3::_val(context).*member = std::move(x3::_attr(context)); };
}

/// Parses `parser` into an attribute of type T (an inline rule; X3 1.74 has no x3::as).
template <typename T>
struct as_tag;
template <typename T, typename Parser>
auto as_impl(Parser parser) {
  return x3::rule<as_tag<T>, T>{"value"} = parser;
}
template <typename T>
constexpr auto as = [](auto parser) { return as_impl<T>(parser); };

/// Where an operand starts.
inline std::size_t where_of(const ast::Operand& operand) {
  return boost::apply_visitor([](const auto& node) { return node.where; }, operand);
}

/// Builds `Node{first, list}` from a sequence (first, list), or passes the operand through
/// unchanged when the list is empty: a plain `1` stays a NumberLiteral instead of nine nested
/// one-operand levels (which made parsing slow and the tree deep). `operand_at` is the index of
/// the operand in the sequence (Expression, Postfix: 0; Prefixed: 1, after its operators).
template <typename Node, int operand_at>
const auto collapse = [](auto& context) {
  auto& attribute = x3::_attr(context);
  auto& operand = boost::fusion::at_c<operand_at>(attribute);
  auto& items = boost::fusion::at_c<1 - operand_at>(attribute);
  if (items.empty()) {
    x3::_val(context) = std::move(operand);
    return;
  }
  Node node;
  node.where = where_of(operand);
  if constexpr (std::is_same_v<Node, ast::Expression>) {
    node.first = std::move(operand);
    node.rest = std::move(items);
  } else if constexpr (std::is_same_v<Node, ast::Postfix>) {
    node.primary = std::move(operand);
    node.ops = std::move(items);
  } else {
    node.ops = std::move(items);
    node.operand = std::move(operand);
  }
  x3::_val(context) = std::move(node);
};

// ---- lexical parts ----
const auto name_char = alnum | char_('_');
auto keyword(const char* word) { return lexeme[lit(word) >> !name_char]; }
const auto reserved = keyword("fn") | keyword("if") | keyword("else") | keyword("for") |
                      keyword("in") | keyword("return") | keyword("include") | keyword("and") |
                      keyword("or") | keyword("not") | keyword("true") | keyword("false");
/// Line breaks allowed inside brackets and after operators.
const auto lb = *eol;
const auto separators = *(eol | ';');

const auto skipper_def = char_(" \t\r") | (lit('#') >> *(~char_('\n')));

const auto identifier_def = (mark >> !reserved >> lexeme[as<std::string>((alpha | char_('_')) >> *name_char)])[into(&ast::Identifier::name)];
const auto number_def = (mark >> number_text)[to_double];
const x3::symbols<char> escapes({{"n", '\n'}, {"t", '\t'}, {"\\", '\\'}, {"\"", '"'}}, "escape sequence (\\n, \\t, \\\\ or \\\")");
const auto escape_def = lit('\\') > escapes;
const auto string_def = (mark >> lexeme[lit('"') > as<std::string>(*(escape | ~char_("\"\\\n"))) > lit('"')])[into(&ast::StringLiteral::value)];
const auto boolean_def = (mark >> as<bool>((keyword("true") >> x3::attr(true)) | (keyword("false") >> x3::attr(false))))[into(&ast::BoolLiteral::value)];
const auto list_def = (mark >> lit('[') > lb > as<std::vector<ast::Expression>>(-(expression >> *((lit(',') >> lb) > expression))) > lb > lit(']'))[into(&ast::ListLiteral::items)];
const auto parenthesized_def = lit('(') > lb > expression > lb > lit(')');
const auto primary_def = number | string | boolean | list | parenthesized | identifier;

// `name = value` or `value`. Each branch is a rule with a semantic action that fills the whole
// node (a rule whose right side holds an action does not propagate attributes by itself).
const auto named_argument_def = (mark >> identifier >> lit('=') >> !lit('=') > expression)[([](auto& context) {
  ast::Argument& node = x3::_val(context);
  node.name = std::move(boost::fusion::at_c<0>(x3::_attr(context)));
  node.value = std::move(boost::fusion::at_c<1>(x3::_attr(context)));
})];
const auto positional_argument_def = (mark >> expression)[([](auto& context) {
  ast::Argument& node = x3::_val(context);
  node.name = boost::none;
  node.value = std::move(x3::_attr(context));
})];
const auto argument_def = named_argument | positional_argument;
const auto call_def = (mark >> lit('(') > lb > as<std::vector<ast::Argument>>(-(argument >> *((lit(',') >> lb) > argument))) > lb > lit(')'))[into(&ast::CallArguments::arguments)];
// `[i]`, `[a:b]`, `[a:]`, `[:b]`, `[:]`: the first expression is parsed once (no backtracking
// over it, which nested subscripts would make exponential).
const auto slice_tail_def =
    (mark >> lit(':') >> lb >> as<boost::optional<ast::Expression>>(-expression))[into(&ast::SliceTail::stop)];
const auto index_or_slice_def = (mark >> expression >> -slice_tail)[([](auto& context) {
  ast::Subscript& node = x3::_val(context);
  auto& tail = boost::fusion::at_c<1>(x3::_attr(context));
  if (tail) {
    node.slice = true;
    node.start = std::move(boost::fusion::at_c<0>(x3::_attr(context)));
    node.stop = std::move(tail->stop);
  } else {
    node.index = std::move(boost::fusion::at_c<0>(x3::_attr(context)));
  }
})];
const auto slice_from_start_def = (mark >> slice_tail)[([](auto& context) {
  x3::_val(context).slice = true;
  x3::_val(context).stop = std::move(x3::_attr(context).stop);
})];
const auto subscript_body_def = index_or_slice | slice_from_start;
const auto subscript_def = (mark >> lit('[') > lb > subscript_body > lb > lit(']'))[([](auto& context) {
  const std::size_t where = x3::_val(context).where;
  x3::_val(context) = std::move(x3::_attr(context));
  x3::_val(context).where = where;
})];
const auto postfix_def = (primary >> *(call | subscript))[collapse<ast::Postfix, 0>];

const x3::symbols<Op> sign_ops({{"-", Op::Neg}, {"+", Op::Pos}}, "sign");
const auto prefix_op_def = sign_ops;
// `not` binds looser than comparisons: `not a == b` is `not (a == b)`.
const auto negation_def = (*(keyword("not") >> x3::attr(Op::Not)) >> comparison)[collapse<ast::Prefixed, 1>];
const auto prefixed_def = (*prefix_op >> postfix)[collapse<ast::Prefixed, 1>];

const x3::symbols<Op> multiplicative_ops({{"*", Op::Mul}, {"/", Op::Div}, {"%", Op::Mod}}, "'*', '/' or '%'");
const x3::symbols<Op> additive_ops({{"+", Op::Add}, {"-", Op::Sub}}, "'+' or '-'");
const x3::symbols<Op> compare_ops({{"==", Op::Eq}, {"!=", Op::Ne}, {"<", Op::Lt}, {"<=", Op::Le},
                                   {">", Op::Gt}, {">=", Op::Ge}},
                                  "comparison");
const auto intersect_op = lit('&') >> x3::attr(Op::Intersect);
const auto union_op = lit('|') >> x3::attr(Op::Union);
const auto and_op = keyword("and") >> x3::attr(Op::And);
const auto or_op = keyword("or") >> x3::attr(Op::Or);

const auto multiplicative_operation_def = (multiplicative_ops >> lb) > prefixed;
const auto additive_operation_def = (additive_ops >> lb) > multiplicative;
const auto intersect_operation_def = (intersect_op >> lb) > additive;
const auto union_operation_def = (union_op >> lb) > intersection;
const auto compare_operation_def = (compare_ops >> lb) > union_;
const auto and_operation_def = (and_op >> lb) > negation;
const auto or_operation_def = (or_op >> lb) > conjunction;
const auto multiplicative_def = (prefixed >> *multiplicative_operation)[collapse<ast::Expression, 0>];
const auto additive_def = (multiplicative >> *additive_operation)[collapse<ast::Expression, 0>];
const auto intersection_def = (additive >> *intersect_operation)[collapse<ast::Expression, 0>];
const auto union__def = (intersection >> *union_operation)[collapse<ast::Expression, 0>];
const auto comparison_def = (union_ >> *compare_operation)[collapse<ast::Expression, 0>];
const auto conjunction_def = (negation >> *and_operation)[collapse<ast::Expression, 0>];
const auto expression_def = conjunction >> *or_operation;

// ---- statements ----
const auto end_of_statement_def = +(eol | ';') | &lit('}') | eoi;
const auto end_of_input_def = eoi;
const auto keyword_in_def = keyword("in");
const auto close_brace_def = lit('}');
const auto not_element_assignment_def = !(lit('=') >> !lit('='));
const auto block_def = (lb >> mark >> lit('{') > as<std::vector<ast::Statement>>(separators >> *(statement > end_of_statement)) > close_brace)[into(&ast::Block::statements)];
const auto assignment_def = identifier >> lit('=') >> !lit('=') > expression;
const auto return_statement_def = (mark >> keyword("return") >> as<boost::optional<ast::Expression>>(-expression))[into(&ast::Return::value)];
const auto include_statement_def = (mark >> keyword("include") > string)[into(&ast::Include::path)];
const auto conditional_def = expression > block;
const auto if_statement_def = ((keyword("if") > conditional) % (lb >> keyword("else"))) >>
                              -(lb >> keyword("else") > block);
const auto for_statement_def = keyword("for") > identifier > keyword_in > expression > block;
const auto function_definition_def =
    keyword("fn") > identifier > lit('(') > lb > -(identifier % (lit(',') >> lb)) > lb > lit(')') > block;
const auto statement_def = function_definition | if_statement | for_statement | return_statement | include_statement |
                           assignment | (expression > not_element_assignment);
const auto program_def = (mark >> as<std::vector<ast::Statement>>(separators >> *(statement > end_of_statement)) > end_of_input)[into(&ast::Program::statements)];

BOOST_SPIRIT_DEFINE(identifier, number, string, escape, boolean, list, parenthesized, primary, argument, named_argument,
                    positional_argument, call, subscript, subscript_body, index_or_slice, slice_from_start, slice_tail,
                    postfix, prefix_op, prefixed, multiplicative, additive, intersection, union_, comparison, negation,
                    conjunction, expression)
BOOST_SPIRIT_DEFINE(multiplicative_operation, additive_operation, intersect_operation,
                    union_operation, compare_operation, and_operation, or_operation)
BOOST_SPIRIT_DEFINE(assignment, return_statement, include_statement, block, conditional, if_statement, for_statement,
                    function_definition, statement, end_of_statement, end_of_input, keyword_in, close_brace,
                    not_element_assignment, skipper, program)

}  // namespace sculpt::language::grammar

namespace sculpt::language {
inline const grammar::program_type& program_rule() { return grammar::program; }
inline const grammar::skipper_type& skipper_rule() { return grammar::skipper; }
}  // namespace sculpt::language
