#pragma once
/// \file sparse_code_stream.h
/// One sparse code (atoms and coefficients over a cosine basis of n^2 atoms) in the model file's byte
/// streams: the layout the height's sections ATOM / COEF and the attributes' AATM / ACOF share
/// (docs/FORMAT.md).
///
/// Lossless: varint count, varint atom indices in selection order; f64 coefficients in that order.
/// Quantised: varint count, varint deltas of the sorted shell ranks (shellRank); svarint coefficients in
/// steps, in rank order (the code is the same sum).
/// Range-coded (quantised files written since the flag was added): the same values through
/// SparseCodeContexts' adaptive models.

#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/range_coder.h>

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Rank of cosine atom (i, j) = (atom / n, atom % n) in "shell order": by max(i, j) first (the Nyquist
  /// cap allows exactly the shells up to a frequency, and OMP picks low shells most), so a code's sorted
  /// ranks form a near-prefix with small deltas. Shell m = max(i, j) holds ranks m^2 .. m^2 + 2m.
  /// With \a monomials atoms after the cosines (QuadricDctDictionary: 5), monomial k (atom n^2 + k) has
  /// rank 1 + k, right after the constant, and the other cosines move up by \a monomials: the quadric's
  /// atoms, in nearly every code, come first.
  int
  shellRank (int atom, int frequencies, int monomials = 0);

  /// The atom of shell rank \a rank (inverse of shellRank).
  int
  atomOfShellRank (int rank, int frequencies, int monomials = 0);

  /// \brief Positions of \a atoms sorted by shell rank: the order quantised files store a code in.
  std::vector<std::size_t>
  shellRankOrder (const std::vector<int>& atoms, int frequencies, int monomials = 0);

  /// \brief A range decoder over every byte \a in has left, named as \a in (\a in is then at its end): a
  /// range-coded section.
  RangeDecoder
  rangeDecoderOverRest (ByteReader& in);

  /// \brief Writes the atoms of a code; returns the order they were written in (positions in \a atoms):
  /// selection order lossless, shell-rank order quantised.
  std::vector<std::size_t>
  putCodeAtoms (ByteWriter& out, const std::vector<int>& atoms, bool quantised, int frequencies, int monomials = 0);

  /// \brief Reads the atoms of a code written by putCodeAtoms. Refuses (ByteReader::fail, naming \a code,
  /// e.g. "patch 3") a count above the basis' size (n^2 + \a monomials) or the bytes left, indices outside
  /// the basis, and repeats.
  void
  getCodeAtoms (ByteReader& in, bool quantised, int frequencies, const std::string& code, std::vector<int>& atoms,
                int monomials = 0);

  /// \brief Writes \a coefficients in \a order: f64 when \a step is 0, else svarint multiples of \a step.
  /// Throws pcl_sparse::Error for a coefficient too large for the step. Returns the values the reader
  /// gets back, in \a order.
  std::vector<double>
  putCodeCoefficients (ByteWriter& out, const std::vector<double>& coefficients, const std::vector<std::size_t>& order,
                       double step);

  /// \brief Reads \a count coefficients written by putCodeCoefficients with \a step; refuses non-finite ones.
  void
  getCodeCoefficients (ByteReader& in, std::size_t count, double step, std::vector<double>& coefficients);

  /// \brief The adaptive models of one stream of range-coded sparse codes (docs/FORMAT.md, "Range-coded
  /// fields"). A code's atoms: their count (a bit tree), then one bit per shell rank from 0 up to its last
  /// atom, each rank with its own probability (low ranks are in most codes, high ones in few). Its
  /// coefficients, in rank order, in steps: a SignedIntegerModel per rank, ranks from 31 up sharing one
  /// (low frequencies carry larger coefficients). Writer and reader must see the same codes in the same order.
  class SparseCodeContexts
  {
  public:
    /// Ranks from this one up share their coefficients' model.
    static constexpr int coefficient_contexts = 32;

    /// \param[in] frequencies  n of the basis (n^2 cosine atoms)
    /// \param[in] monomials    monomial atoms after them (shellRank)
    explicit SparseCodeContexts (int frequencies, int monomials = 0);

    /// Codes \a atoms (distinct, < n^2); returns the order they were coded in: by shell rank.
    std::vector<std::size_t>
    putAtoms (RangeEncoder& out, const std::vector<int>& atoms);

    /// Decodes a code's atoms, in shell-rank order. Refuses (RangeDecoder::fail, naming \a code) a count
    /// above n^2.
    void
    getAtoms (RangeDecoder& in, const std::string& code, std::vector<int>& atoms);

    /// Codes \a coefficients in \a order (putAtoms' order) as multiples of \a step (> 0); \a atoms gives
    /// their ranks. Returns the values the reader gets back, in \a order. Throws pcl_sparse::Error for a
    /// coefficient too large for the step.
    std::vector<double>
    putCoefficients (RangeEncoder& out, const std::vector<int>& atoms, const std::vector<double>& coefficients,
                     const std::vector<std::size_t>& order, double step);

    /// Decodes the coefficients of \a atoms (as getAtoms gave them) with \a step.
    void
    getCoefficients (RangeDecoder& in, const std::vector<int>& atoms, double step, std::vector<double>& coefficients);

  private:
    int frequencies_;
    int monomials_;
    BitTreeModel count_;
    std::vector<AdaptiveBit> present_;                ///< per shell rank
    std::vector<SignedIntegerModel> coefficient_;     ///< per shell rank below coefficient_contexts, then shared
  };
} // namespace pcl_sparse
