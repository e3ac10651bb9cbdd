#pragma once
/// \file error_handler.hpp
/// Position tagging for the grammar (grammar-only header). Every rule ID derives from
/// `annotate_position`, which stores in each syntax-tree node the byte offset where the node's
/// text starts. Expectation failures (`a > b`) are not handled here: they leave the parser as
/// x3::expectation_failure and grammar.cpp turns them into ScriptError with our own
/// `file:line:col: error: expected X here` formatting (the stock X3 handler prints no column).

#include <boost/spirit/home/x3.hpp>

#include <type_traits>

#include "language/ast.hpp"

namespace sculpt::language::grammar {
namespace x3 = boost::spirit::x3;

/// Where the text being parsed begins.
struct PositionTracker {
  const char* begin = nullptr;
};
struct position_tag;

struct annotate_position {
  template <typename Iterator, typename Attribute, typename Context>
  void on_success(const Iterator& first, const Iterator& /*last*/, Attribute& node,
                  const Context& context) const {
    if constexpr (std::is_base_of_v<ast::Node, Attribute>) {
      const PositionTracker& tracker = x3::get<position_tag>(context).get();
      node.where = static_cast<std::size_t>(first - tracker.begin);
    }
  }
};

}  // namespace sculpt::language::grammar
