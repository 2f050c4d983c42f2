// TIE attention from receiver/sender tokens without per-edge features
// (see tie_attention.h for the algebra).
#include "tie_attention.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "layers/core/error.h"

namespace layers::layersnet {
namespace {

void require(bool ok, const std::string& what, const at::Tensor& t) {
  if (ok) return;
  std::ostringstream s;
  s << "tie_attention: " << what << ", got " << (t.defined() ? t.sizes() : at::IntArrayRef{});
  throw Error(s.str());
}

// Centred tokens and their variance over the last dimension.
struct Centred {
  at::Tensor x, var;
  explicit Centred(const at::Tensor& t) : x(t - t.mean(-1, true)), var(x.pow(2).mean(-1)) {}
};

// sd of e = r + s from the variances and the cross term (clamped: rounding
// may make a tiny variance negative).
at::Tensor spread(const at::Tensor& var_sum, const at::Tensor& cross, double eps) {
  return (var_sum + 2 * cross).clamp_min(0).add(eps).sqrt();
}

// [N,d] -> [H,N,dh]
at::Tensor split_heads(const at::Tensor& x, std::int64_t heads) {
  return x.reshape({x.size(0), heads, -1}).permute({1, 0, 2});
}

}  // namespace

at::Tensor tie_attention(const at::Tensor& q, const at::Tensor& r, const TieSenders& senders, const TieWeights& w) {
  require(q.dim() == 2, "q must be [P,d]", q);
  const std::int64_t P = q.size(0), d = q.size(1), H = w.heads;
  require(H > 0 && d % H == 0, "heads must divide the width " + std::to_string(d), q);
  require(r.sizes() == q.sizes(), "r must match q [P,d]", r);
  require(w.wk.dim() == 2 && w.wk.size(0) == d && w.wk.size(1) == d, "wk must be [d,d]", w.wk);
  require(w.wv.dim() == 2 && w.wv.size(0) == d && w.wv.size(1) == d, "wv must be [d,d]", w.wv);
  const at::Tensor& s = senders.dense;
  require(s.dim() == 2 && s.size(1) == d, "dense senders must be [S,d]", s);
  const std::int64_t S = s.size(0);
  const at::Tensor& md = senders.dense_mask;
  require(md.dim() == 3 && md.size(1) == P && md.size(2) == S && md.scalar_type() == at::kBool,
          "dense mask must be bool [G,P,S]", md);
  const std::int64_t G = md.size(0);
  require(G > 0 && H % G == 0, "head groups must divide the heads", md);
  const bool has_local = senders.local.defined() && senders.local_index.defined() && senders.local_index.size(1) > 0;
  if (senders.local.defined()) {
    require(senders.local.dim() == 2 && senders.local.size(1) == d, "local senders must be [B,d]", senders.local);
    const at::Tensor& idx = senders.local_index;
    require(idx.defined() && idx.dim() == 2 && idx.size(0) == P && idx.scalar_type() == at::kLong,
            "local index must be int64 [P,K]", idx);
    const at::Tensor& ml = senders.local_mask;
    require(ml.defined() && ml.dim() == 3 && ml.size(0) == G && ml.size(1) == P && ml.size(2) == idx.size(1) &&
                ml.scalar_type() == at::kBool,
            "local mask must be bool [G,P,K]", ml);
  }
  const std::int64_t dh = d / H;
  const double scale = 1.0 / std::sqrt(static_cast<double>(dh));

  const Centred rc(r), sc(s);
  const at::Tensor qh = split_heads(q, H);                                        // [H,P,dh]
  const at::Tensor q_kr = (qh * split_heads(at::linear(rc.x, w.wk), H)).sum(-1);  // [H,P]

  // Dense block: sd [P,S], logits [H,P,S].
  const at::Tensor sd_d = spread(rc.var.unsqueeze(1) + sc.var.unsqueeze(0), at::matmul(rc.x, sc.x.t()) / d, w.eps);
  const at::Tensor ks = split_heads(at::linear(sc.x, w.wk), H);  // [H,S,dh]
  at::Tensor logits = (q_kr.unsqueeze(2) + at::bmm(qh, ks.transpose(1, 2))) / sd_d.unsqueeze(0) * scale;
  at::Tensor mask = md.repeat_interleave(H / G, 0);  // [H,P,S]

  // Local block: per-token work on [B,d], gathered to the slots: sd
  // [P,K], logits [H,P,K].
  at::Tensor sd_l, vl;
  if (has_local) {
    const std::int64_t K = senders.local_index.size(1);
    const at::Tensor flat = senders.local_index.reshape({-1});
    auto gather = [&](const at::Tensor& t) { return t.index_select(0, flat).reshape({P, K, -1}); };
    const Centred lc(senders.local);  // [B,d], [B]
    // A product per (patch, slot) pair, as one element-wise product and sum:
    // bmm over P batches of [K,d] x [d,1] runs one small product per patch
    // on the CPU (about 260 operator calls per block, twice that backward).
    const at::Tensor cross = (gather(lc.x) * rc.x.unsqueeze(1)).sum(2) / d;  // [P,K]
    sd_l = spread(rc.var.unsqueeze(1) + gather(lc.var.unsqueeze(1)).squeeze(2), cross, w.eps);
    const at::Tensor kl = gather(at::linear(lc.x, w.wk)).reshape({P, K, H, dh});
    const at::Tensor q_kl = (kl * q.reshape({P, 1, H, dh})).sum(-1).permute({2, 0, 1});  // [H,P,K]
    logits = at::cat({logits, (q_kr.unsqueeze(2) + q_kl) / sd_l.unsqueeze(0) * scale}, 2);
    mask = at::cat({mask, senders.local_mask.repeat_interleave(H / G, 0)}, 2);
    vl = gather(at::linear(lc.x, w.wv)).reshape({P, K, H, dh});
  }

  // Masked softmax; a row with no allowed sender gets all-zero weights.
  const at::Tensor masked = logits.masked_fill(mask.logical_not(), -std::numeric_limits<float>::infinity());
  at::Tensor top = std::get<0>(masked.max(2, true)).detach();
  top = at::where(at::isfinite(top), top, at::zeros_like(top));
  const at::Tensor e = (masked - top).exp();
  const at::Tensor total = e.sum(2, true);
  const at::Tensor a = e / (total + (total == 0).to(total.scalar_type()));  // [H,P,S(+K)]; empty rows: 0 / 1

  const at::Tensor a_d = a.narrow(2, 0, S);
  const at::Tensor w_d = a_d / sd_d.unsqueeze(0);                         // a / sd, [H,P,S]
  at::Tensor w_sum = w_d.sum(2);                                          // [H,P]
  at::Tensor out = at::bmm(w_d, split_heads(at::linear(sc.x, w.wv), H));  // [H,P,dh]
  if (has_local) {
    const at::Tensor w_l = a.narrow(2, S, a.size(2) - S) / sd_l.unsqueeze(0);  // [H,P,K]
    w_sum = w_sum + w_l.sum(2);
    out = out + (vl * w_l.permute({1, 2, 0}).unsqueeze(3)).sum(1).permute({1, 0, 2});
  }
  out = out + split_heads(at::linear(rc.x, w.wv), H) * w_sum.unsqueeze(2);
  if (w.bv.defined()) out = out + w.bv.reshape({H, 1, dh}) * a.sum(2, true);
  return out.permute({1, 0, 2}).reshape({P, d});
}

}  // namespace layers::layersnet
