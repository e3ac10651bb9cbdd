#pragma once
/// \file config.hpp
/// Iterator and context types of the grammar (X3 rexpr_full layout). Grammar-only header.

#include <boost/spirit/home/x3.hpp>

#include <functional>

#include "language/grammar/error_handler.hpp"

namespace sculpt::language::grammar {
namespace x3 = boost::spirit::x3;

using iterator_type = const char*;
using skipper_type = x3::rule<class skipper_class>;
using phrase_context_type = x3::phrase_parse_context<skipper_type>::type;
using context_type =
    x3::context<position_tag, std::reference_wrapper<PositionTracker>, phrase_context_type>;

}  // namespace sculpt::language::grammar
