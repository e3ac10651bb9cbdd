#pragma once
/// \file ast_adapted.hpp
/// Boost.Fusion adaptation of the syntax tree, so that X3 can fill it. One-member nodes are filled by a
/// semantic action instead (grammar_def.hpp `into`). Included only by the
/// grammar. `where` is not adapted: the grammar's on_success handler sets it.

#include <boost/fusion/include/adapt_struct.hpp>

#include "language/ast.hpp"

BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::Operation, op, operand)
BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::Expression, first, rest)
BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::Postfix, primary, ops)
BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::Prefixed, ops, operand)
BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::Assignment, target, value)
BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::ConditionalBlock, condition, body)
BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::If, branches, otherwise)
BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::For, variable, sequence, body)
BOOST_FUSION_ADAPT_STRUCT(sculpt::language::ast::FunctionDefinition, name, parameters, body)
