// The efficient TIE attention (plugins/layersnet/src/tie_attention.h) against a
// naive dense reference that materialises every edge e_ij = r_i + s_j,
// layer-normalises it, maps it to keys and values and runs a masked
// softmax per head.
#include <gtest/gtest.h>

#include <limits>

#include "layers/core/error.h"
#include "tie_attention.h"

namespace ln = layers::layersnet;

namespace {

// Senders of receiver i: every dense sender, then its own local slots.
at::Tensor naive_attention(const at::Tensor& q, const at::Tensor& r, const ln::TieSenders& s, const ln::TieWeights& w) {
  const std::int64_t P = q.size(0), d = q.size(1), H = w.heads, dh = d / H, S = s.dense.size(0);
  const std::int64_t G = s.dense_mask.size(0);
  at::Tensor senders = s.dense.unsqueeze(0).expand({P, S, d});
  at::Tensor mask = s.dense_mask;
  if (s.local.defined()) {  // receiver i's slots, as [P,K,d]
    const at::Tensor slots = s.local.index_select(0, s.local_index.reshape({-1}));
    senders = at::cat({senders, slots.reshape({P, s.local_index.size(1), d})}, 1);
    mask = at::cat({mask, s.local_mask}, 2);
  }
  const at::Tensor e = r.unsqueeze(1) + senders;  // [P,N,d], materialised
  const at::Tensor mean = e.mean(-1, true);
  const at::Tensor var = (e - mean).pow(2).mean(-1, true);
  const at::Tensor e_hat = (e - mean) / (var + w.eps).sqrt();
  const at::Tensor k = at::matmul(e_hat, w.wk.t()) + w.bk;  // [P,N,d]
  const at::Tensor v = at::matmul(e_hat, w.wv.t()) + w.bv;
  at::Tensor out = at::zeros({P, d}, q.options());
  for (std::int64_t h = 0; h < H; ++h) {
    const at::Tensor qh = q.narrow(1, h * dh, dh), kh = k.narrow(2, h * dh, dh), vh = v.narrow(2, h * dh, dh);
    const at::Tensor allowed = mask[h / (H / G)];  // [P,N]
    for (std::int64_t i = 0; i < P; ++i) {
      if (!allowed[i].any().item<bool>()) continue;  // no sender: zero output
      at::Tensor logits = at::matmul(kh[i], qh[i]) / std::sqrt(static_cast<double>(dh));
      logits = logits.masked_fill(allowed[i].logical_not(), -std::numeric_limits<double>::infinity());
      const at::Tensor a = at::softmax(logits, 0);
      out[i].narrow(0, h * dh, dh).copy_(at::matmul(a, vh[i]));
    }
  }
  return out;
}

struct Case {
  at::Tensor q, r;
  ln::TieSenders senders;
  ln::TieWeights w;
};

// P receivers, S dense senders, K local slots over B local tokens, width
// d, H heads, G = 2 groups; random masks with some empty rows.
Case random_case(std::int64_t P, std::int64_t S, std::int64_t K, std::int64_t d, std::int64_t H, at::ScalarType type,
                 std::uint64_t seed, std::int64_t B = 4) {
  at::manual_seed(seed);
  const at::TensorOptions o = at::TensorOptions().dtype(type);
  Case c;
  c.q = at::randn({P, d}, o);
  c.r = at::randn({P, d}, o) * 0.5 + 0.3;
  c.senders.dense = at::randn({S, d}, o) * 2.0;
  c.senders.dense_mask = at::rand({2, P, S}) < 0.5;
  if (K > 0) {
    c.senders.local = at::randn({B, d}, o);
    c.senders.local_index = at::randint(B, {P, K}, at::kLong);
    c.senders.local_mask = at::rand({2, P, K}) < 0.5;
  }
  // Row 0 of group 0 and row 1 of both groups have no sender at all.
  c.senders.dense_mask[0][0].fill_(false);
  c.senders.dense_mask.select(1, 1).fill_(false);
  if (K > 0) {
    c.senders.local_mask[0][0].fill_(false);
    c.senders.local_mask.select(1, 1).fill_(false);
  }
  c.w.wk = at::randn({d, d}, o) / std::sqrt(static_cast<double>(d));
  c.w.bk = at::randn({d}, o);
  c.w.wv = at::randn({d, d}, o) / std::sqrt(static_cast<double>(d));
  c.w.bv = at::randn({d}, o);
  c.w.heads = H;
  return c;
}

double max_abs(const at::Tensor& a) { return a.abs().max().item<double>(); }

}  // namespace

TEST(TieAttention, MatchesNaiveDenseReference) {
  for (std::int64_t K : {0, 3}) {
    Case c = random_case(7, 9, K, 16, 4, at::kFloat, 11 + K);
    const at::Tensor fast = ln::tie_attention(c.q, c.r, c.senders, c.w);
    const at::Tensor slow = naive_attention(c.q, c.r, c.senders, c.w);
    ASSERT_EQ(fast.sizes(), slow.sizes());
    ASSERT_TRUE(at::isfinite(fast).all().item<bool>()) << fast;
    EXPECT_LT(max_abs(fast - slow), 1e-5) << "K=" << K << "\n" << fast - slow;
    // The rows without senders are zero in the heads concerned.
    EXPECT_EQ(max_abs(fast[1]), 0.0);
    EXPECT_EQ(max_abs(fast[0].narrow(0, 0, 8)), 0.0);  // heads 0, 1 (group 0)
    EXPECT_GT(max_abs(fast[0].narrow(0, 8, 8)), 0.0);  // heads 2, 3 (group 1) have senders
  }
}

TEST(TieAttention, MatchesNaiveReferenceAtLargerSizesInDoublePrecision) {
  Case c = random_case(20, 31, 5, 32, 8, at::kDouble, 5, 30);
  const at::Tensor fast = ln::tie_attention(c.q, c.r, c.senders, c.w);
  const at::Tensor slow = naive_attention(c.q, c.r, c.senders, c.w);
  EXPECT_LT(max_abs(fast - slow), 1e-10);
}

namespace {

// Gradients of q, r and both sender blocks against the reference.
void expect_same_gradients(at::ScalarType type, double tolerance) {
  Case c = random_case(6, 5, 2, 8, 2, type, 3);
  auto grads = [&](bool efficient) {
    at::Tensor q = c.q.clone().requires_grad_(), r = c.r.clone().requires_grad_();
    ln::TieSenders s = c.senders;
    s.dense = c.senders.dense.clone().requires_grad_();
    s.local = c.senders.local.clone().requires_grad_();
    const at::Tensor out = efficient ? ln::tie_attention(q, r, s, c.w) : naive_attention(q, r, s, c.w);
    (out * at::cos(at::arange(out.numel(), out.options()).reshape(out.sizes()))).sum().backward();
    return std::vector<at::Tensor>{q.grad(), r.grad(), s.dense.grad(), s.local.grad()};
  };
  const auto fast = grads(true), slow = grads(false);
  for (std::size_t i = 0; i < fast.size(); ++i) {
    ASSERT_TRUE(at::isfinite(fast[i]).all().item<bool>()) << type << " gradient " << i;
    EXPECT_LT(max_abs(fast[i] - slow[i]), tolerance) << type << " gradient " << i;
  }
  EXPECT_EQ(max_abs(fast[0][1]), 0.0);  // row 1 attends to nothing
}

}  // namespace

TEST(TieAttention, GradientsMatchTheReferenceAndStayFinite) {
  expect_same_gradients(at::kDouble, 1e-9);
  expect_same_gradients(at::kFloat, 1e-4);
}

TEST(TieAttention, RejectsInconsistentShapes) {
  Case c = random_case(4, 3, 0, 8, 2, at::kFloat, 1);
  ln::TieSenders bad = c.senders;
  bad.dense_mask = bad.dense_mask.narrow(1, 0, 3);
  EXPECT_THROW(ln::tie_attention(c.q, c.r, bad, c.w), layers::Error);
  ln::TieWeights odd = c.w;
  odd.heads = 3;
  EXPECT_THROW(ln::tie_attention(c.q, c.r, c.senders, odd), layers::Error);
}
