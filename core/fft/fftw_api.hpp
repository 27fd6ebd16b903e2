// FFTW's double and single precision APIs behind one name, Fftw<double> and Fftw<float>, so
// code over real transforms (core/fft/fft's plans, the bench's bare reference pairs) is written
// once for both precisions. Only for code that calls FFTW itself: the rest of pinmask uses
// core/fft/fft.
#pragma once

#include <fftw3.h>

#include <cstddef>

namespace pinmask {

template <class T>
struct Fftw;

template <>
struct Fftw<double> {
    using Real = double;
    using Complex = fftw_complex;
    using PlanT = fftw_plan;
    static double* alloc_real(std::size_t n) { return fftw_alloc_real(n); }
    static Complex* alloc_complex(std::size_t n) { return fftw_alloc_complex(n); }
    static void free(void* p) { fftw_free(p); }
    static void plan_with_nthreads(int n) { fftw_plan_with_nthreads(n); }
    static PlanT r2c(int r, int c, double* in, Complex* out, unsigned f) {
        return fftw_plan_dft_r2c_2d(r, c, in, out, f);
    }
    static PlanT c2r(int r, int c, Complex* in, double* out, unsigned f) {
        return fftw_plan_dft_c2r_2d(r, c, in, out, f);
    }
    static void execute(PlanT p) { fftw_execute(p); }
    static void execute_r2c(void* p, double* in, Complex* out) {
        fftw_execute_dft_r2c(static_cast<PlanT>(p), in, out);
    }
    static void execute_c2r(void* p, Complex* in, double* out) {
        fftw_execute_dft_c2r(static_cast<PlanT>(p), in, out);
    }
    static void destroy(PlanT p) { fftw_destroy_plan(p); }
};

template <>
struct Fftw<float> {
    using Real = float;
    using Complex = fftwf_complex;
    using PlanT = fftwf_plan;
    static float* alloc_real(std::size_t n) { return fftwf_alloc_real(n); }
    static Complex* alloc_complex(std::size_t n) { return fftwf_alloc_complex(n); }
    static void free(void* p) { fftwf_free(p); }
    static void plan_with_nthreads(int n) { fftwf_plan_with_nthreads(n); }
    static PlanT r2c(int r, int c, float* in, Complex* out, unsigned f) {
        return fftwf_plan_dft_r2c_2d(r, c, in, out, f);
    }
    static PlanT c2r(int r, int c, Complex* in, float* out, unsigned f) {
        return fftwf_plan_dft_c2r_2d(r, c, in, out, f);
    }
    static void execute(PlanT p) { fftwf_execute(p); }
    static void execute_r2c(void* p, float* in, Complex* out) {
        fftwf_execute_dft_r2c(static_cast<PlanT>(p), in, out);
    }
    static void execute_c2r(void* p, Complex* in, float* out) {
        fftwf_execute_dft_c2r(static_cast<PlanT>(p), in, out);
    }
    static void destroy(PlanT p) { fftwf_destroy_plan(p); }
};

}  // namespace pinmask
