#pragma once
// weightedSpectrumSum: the inverse-distance mix of source spectra that fills
// an empty ortho pixel (OrthoTileAccumulator::finish),
//   out[b] = sum over k = 0 .. count-1 of weights[k] * (sources[k][b] * scales[k]),
// each band summed from 0 in the order of k: exactly the floats of a loop over
// the sources with an inner loop over the bands, whatever the vector width.
//
// Why its own function: it is the gap filling's inner loop (about a dozen
// sources of ~200 bands for each of millions of filled pixels). Bands go in
// blocks held in registers across the sources instead of loading and
// storing the running sum once per source, and the function is compiled
// for AVX2 as well as the baseline (chosen at run time): 8 floats an
// instruction instead of 4. Multiplications and additions stay separate
// (no fused multiply-add), so both versions give the same bits.

namespace hsmap {

void weightedSpectrumSum(const float* const* sources, const float* weights, const float* scales, int count,
                         int bands, float* out);

}  // namespace hsmap
