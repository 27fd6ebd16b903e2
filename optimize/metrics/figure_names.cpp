#include "optimize/metrics/figure_names.hpp"

#include <map>

namespace pinmask {

std::string figure_words(const std::string& name) {
    static const std::map<std::string, std::string> words{
        {"analytic_mmse_psnr_db", "analytic MMSE PSNR"},
        {"analytic_wiener_psnr_db", "analytic Wiener PSNR"},
        {"analytic_robust_mmse_psnr_db", "robust analytic MMSE PSNR"},
        {"analytic_robust_wiener_psnr_db", "robust analytic Wiener PSNR"},
        {"analytic_robust_filter_psnr_db", "robust-filter analytic PSNR"},
        {"sim_wiener_psnr_db", "simulated Wiener PSNR"},
        {"sim_tv_psnr_db", "simulated TV-L2 PSNR"}};
    const auto it = words.find(name);
    return it == words.end() ? name : it->second;
}

}  // namespace pinmask
