// plugins/layersnet/src/tie_attention.h -- masked multi-head attention in TIE
// form (Transformer with Implicit Edges), computed without materialising
// per-edge feature tensors.
//
// Receiver i has a query q_i and a receiver token r_i; sender j has a
// sender token s_j. The edge i<-j is e_ij = r_i + s_j, layer-normalised
// without affine over its width d: e^_ij = (e_ij - mean(e_ij)) / sd_ij.
// Keys and values are linear maps of it: k_ij = Wk e^_ij + bk,
// v_ij = Wv e^_ij + bv, split into H heads of d/H channels; the attention
// of head h is softmax_j(q^h_i . k^h_ij / sqrt(d/H)) over the senders its
// mask allows, and the output is sum_j a^h_ij v^h_ij (zero for a row with
// no allowed sender). With r~, s~ the centred tokens,
//   sd_ij^2 = var(r_i) + var(s_j) + 2 r~_i.s~_j / d
//   q.k_ij  = (q.Wk r~_i + q.Wk s~_j) / sd_ij + q.bk   (q.bk: same for every j, drops out of the softmax)
//   out_i   = Wv r~_i sum_j a_ij/sd_ij + sum_j (a_ij/sd_ij) Wv s~_j + bv sum_j a_ij
// so only [H,P,S] scalars (and r~ s~^T) are formed.
//
// Senders come in two blocks, one softmax over both:
//   dense  s [S,d] shared by every receiver, mask [G,P,S];
//   local  tokens s [B,d] of which receiver i sees its own K slots
//          index[i,0..K) (e.g. a patch's nearby body vertices), mask
//          [G,P,K]; K and B may be 0. Centring and the key/value maps run
//          once per token ([B,d]); only the slots' results are gathered.
// Masks are boolean, G head groups of H/G consecutive heads each.
#pragma once

#include <ATen/ATen.h>

namespace layers::layersnet {

struct TieWeights {
  at::Tensor wk, bk;  // [d,d], [d]  (torch Linear layout: y = x wk^T + bk)
  at::Tensor wv, bv;  // [d,d], [d]
  std::int64_t heads = 1;
  double eps = 1e-5;  // layer-norm epsilon, added to the variance
};

struct TieSenders {
  at::Tensor dense, dense_mask;               // [S,d], [G,P,S]
  at::Tensor local, local_index, local_mask;  // [B,d], [P,K] int64 rows of local, [G,P,K]; undefined: none
};

// q, r: [P,d]. Returns [P,d] (heads concatenated). Throws layers::Error on
// inconsistent shapes.
at::Tensor tie_attention(const at::Tensor& q, const at::Tensor& r, const TieSenders& senders, const TieWeights& w);

}  // namespace layers::layersnet
