#pragma once
// The Cartesian product of two type lists, for TEMPLATE_LIST_TEST_CASE over
// parameterization x scalar (or parameterization x parameterization).
//
//   using Cases = Product<std::tuple<A, B>, std::tuple<double, float>>;
//   // std::tuple<Pair<A, double>, Pair<A, float>, Pair<B, double>, Pair<B, float>>
//   TEMPLATE_LIST_TEST_CASE("...", "[...]", Cases) { using P = typename TestType::First; ... }

#include <tuple>
#include <utility>

namespace tumble::test {

template <class A, class B> struct Pair {
  using First = A;
  using Second = B;
};

namespace detail_product {
template <class A, class List> struct Row;
template <class A, class... Bs> struct Row<A, std::tuple<Bs...>> {
  using type = std::tuple<Pair<A, Bs>...>;
};
template <class ListA, class ListB> struct Product;
template <class... As, class ListB> struct Product<std::tuple<As...>, ListB> {
  using type = decltype(std::tuple_cat(std::declval<typename Row<As, ListB>::type>()...));
};
}  // namespace detail_product

template <class ListA, class ListB>
using Product = typename detail_product::Product<ListA, ListB>::type;

}  // namespace tumble::test
