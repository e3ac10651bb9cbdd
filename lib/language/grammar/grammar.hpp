#pragma once
/// \file grammar.hpp
/// Declaration of the sculpt grammar's start rule and skipper (X3 rexpr_full layout).
/// Grammar-only header: include parser.hpp elsewhere.

#include <boost/spirit/home/x3.hpp>

#include "language/ast.hpp"
#include "language/grammar/config.hpp"

namespace sculpt::language::grammar {
namespace x3 = boost::spirit::x3;

struct program_class;
using program_type = x3::rule<program_class, ast::Program>;
BOOST_SPIRIT_DECLARE(program_type)

}  // namespace sculpt::language::grammar

namespace sculpt::language {
grammar::program_type const& program_rule();
grammar::skipper_type const& skipper_rule();
}  // namespace sculpt::language
