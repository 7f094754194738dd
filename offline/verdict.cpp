// verdict.cpp - how well a bake's Gaussian model holds its exemplar, from measured signals, with what
// the user can do about it. The thresholds and where they come from are in dsn/bake.h (BakeVerdict) and
// the README.
#include "bake_internal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dsn {
namespace {

// A decorrelated channel counts when its variance is at least this share of the strongest one's.
const double kVisibleVariance = 0.1;

std::string format(const char *pattern, double value) {
    char text[256];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// Offset of torus index i on a side of `size` points, in (-size/2, size/2].
int signed_offset(int index, int size) { return index > size / 2 ? index - size : index; }

// Distance of a lag in the support's own metric: Chebyshev for the square, Euclidean (rounded up) for
// the disk, so that the noise of a texton of radius r reaches exactly the lags at distance <= 2r.
int lag_distance(int dx, int dy, uint32_t shape) {
    if (shape == DSN_SHAPE_DISK) return int(std::ceil(std::sqrt(double(dx) * dx + double(dy) * dy) - 1e-9));
    return std::max(std::abs(dx), std::abs(dy));
}

// Sample skewness and excess kurtosis of component k of the exemplar.
void marginal_moments(const Image &exemplar, const ColourBasis &basis, int k, ChannelMarginal &marginal) {
    const size_t plane = size_t(exemplar.width) * size_t(exemplar.height);
    std::vector<double> values(plane, 0.0);
    for (int c = 0; c < exemplar.channels; c++) {
        const double weight = basis.vectors[size_t(c * 3 + k)];
        for (size_t i = 0; i < plane; i++) values[i] += weight * exemplar.values[size_t(c) * plane + i];
    }
    double mean = 0;
    for (double value : values) mean += value;
    mean /= double(plane);
    double m2 = 0, m3 = 0, m4 = 0;
    for (double value : values) {
        const double d = value - mean, square = d * d;
        m2 += square;
        m3 += square * d;
        m4 += square * square;
    }
    m2 /= double(plane), m3 /= double(plane), m4 /= double(plane);
    marginal.variance = m2;
    if (m2 > 0) {
        marginal.skewness = m3 / (m2 * std::sqrt(m2));
        marginal.excess_kurtosis = m4 / (m2 * m2) - 3;
    }
}

// Bytes of the asset a bake at `radius` writes: the bake's own fields with a texton (and, when the bake
// has them, a pyramid and a lattice texton) of that size.
size_t asset_bytes_at(const BakeResult &result, int radius) {
    AssetFields fields = result.fields;
    fields.width = fields.height = uint32_t(2 * radius + 1);
    fields.texton.assign(size_t(fields.width) * fields.height * fields.channels, 0);
    if (!fields.pyramid.empty()) fields.pyramid = texton_pyramid(fields);
    if (!fields.lattice_texton.empty()) set_lattice_texton(fields);
    return encode_asset(fields).size();
}

// Bytes the histogram mapping adds to this bake's asset: the section header and its tables.
size_t histogram_table_bytes(const BakeResult &result) {
    const size_t levels = std::min<size_t>(1 + result.fields.pyramid.size(), DSN_HISTOGRAM_MAX_LEVELS);
    return DSN_SECTION_HEADER_SIZE + DSN_HISTOGRAM_HEADER_SIZE +
           2 * levels * result.fields.channels * size_t(kHistogramEntries);
}

bool has_finding(const BakeVerdict &verdict, VerdictFinding finding) {
    return std::find(verdict.findings.begin(), verdict.findings.end(), finding) != verdict.findings.end();
}

} // namespace

BakeVerdict bake_verdict(const Image &exemplar, const BakeResult &result, const BakeOptions &options) {
    BakeVerdict verdict;
    verdict.rme = result.rme;
    verdict.rme_luminance = result.rme_luminance;
    verdict.rme_effective = result.rme_effective;
    const GaussianModel &model = result.model;
    const int width = model.width, height = model.height;
    const size_t plane = size_t(width) * size_t(height);

    // Decorrelated channels: their marginals and autocorrelations (IDFT of |P_k|^2, P_k the model's
    // spectrum in the component basis). A histogram-preserving bake's model is already in that basis,
    // Gaussianized to unit variance: its channels are rescaled to the components' variances.
    const ColourBasis basis = principal_components(exemplar);
    Spectrum power;
    power.width = width, power.height = height, power.channels = basis.channels;
    power.values.assign(plane * size_t(basis.channels), 0.0f);
    for (int k = 0; k < basis.channels; k++) {
        double model_variance = 0;
        for (size_t i = 0; i < plane; i++) {
            std::complex<double> component = 0;
            for (int c = 0; c < model.channels; c++) {
                const double weight = options.histogram ? double(c == k) : basis.vectors[size_t(c * 3 + k)];
                component += weight * std::complex<double>(model.spectrum.values[size_t(c) * plane + i]);
            }
            power.values[size_t(k) * plane + i] = float(std::norm(component));
            model_variance += std::norm(component) / double(plane);
        }
        if (options.histogram && model_variance > 0)
            for (size_t i = 0; i < plane; i++)
                power.values[size_t(k) * plane + i] *= float(basis.variances[size_t(k)] / model_variance);
    }
    const Image autocorrelation = inverse_dft(power);

    const int reach = 2 * options.radius; // the noise of a texton of radius r correlates lags up to 2r
    const int largest_distance = lag_distance(width / 2, height / 2, options.shape);
    std::vector<double> ring_energy(size_t(largest_distance) + 1, 0.0), ring_peak(ring_energy.size(), 0.0);
    std::vector<size_t> ring_count(ring_energy.size(), 0);
    double total_variance = 0, noise_per_lag = 0, total_energy = 0;
    for (int k = 0; k < basis.channels; k++) {
        ChannelMarginal marginal;
        marginal_moments(exemplar, basis, k, marginal);
        const double *a = &autocorrelation.values[size_t(k) * plane];
        const double variance = a[0];
        total_variance += variance;
        // Standard errors of the sample skewness and excess kurtosis of a Gaussian field with this
        // autocorrelation: sqrt(6 sum rho^3 / N) and sqrt(24 sum rho^4 / N) (the Hermite expansion of the
        // two statistics; 6/N and 24/N for independent samples). |rho|^3 keeps the first an upper bound.
        double cubes = 0, fourths = 0, inside_energy = 0;
        for (size_t i = 0; i < plane && variance > 0; i++) {
            const double rho = a[i] / variance;
            cubes += std::fabs(rho * rho * rho);
            fourths += rho * rho * rho * rho;
        }
        marginal.skewness_error = std::sqrt(6 * std::max(1.0, cubes) / double(plane));
        marginal.kurtosis_error = std::sqrt(24 * std::max(1.0, fourths) / double(plane));
        verdict.channels.push_back(marginal);
        for (int y = 0; y < height; y++)
            for (int x = 0; x < width; x++) {
                const int distance =
                    lag_distance(signed_offset(x, width), signed_offset(y, height), options.shape);
                if (distance <= reach)
                    inside_energy +=
                        a[size_t(y) * size_t(width) + size_t(x)] * a[size_t(y) * size_t(width) + size_t(x)];
            }
        // Bartlett: a sample autocorrelation's variance at any lag is about (1/N) sum_y A(y)^2; the energy
        // within reach stands for that sum.
        noise_per_lag += inside_energy / double(plane);
    }
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            double sum = 0;
            for (int k = 0; k < basis.channels; k++)
                sum += autocorrelation.values[size_t(k) * plane + size_t(y) * size_t(width) + size_t(x)];
            const int distance =
                lag_distance(signed_offset(x, width), signed_offset(y, height), options.shape);
            const size_t ring = size_t(std::min(distance, largest_distance));
            ring_energy[ring] += sum * sum;
            ring_count[ring]++;
            total_energy += sum * sum;
            if (total_variance > 0) ring_peak[ring] = std::max(ring_peak[ring], sum / total_variance);
        }
    // Energy beyond reach, less what sampling noise alone puts there.
    double beyond = 0;
    size_t lags_beyond = 0;
    for (size_t d = size_t(reach) + 1; d < ring_energy.size(); d++) {
        beyond += ring_energy[d] - double(ring_count[d]) * noise_per_lag;
        lags_beyond += ring_count[d];
    }
    verdict.structure_beyond_reach = total_energy > 0 ? std::max(0.0, beyond) / total_energy : 0;
    // Sampling noise alone leaves that corrected energy within about 3 of its standard deviations of 0.
    // The energy over the lags is (1/N) sum P^2 over the frequencies (Parseval), P the periodogram, about
    // S times an exponential variable (S the spectrum, P(xi) = P(-xi)): its noise has a standard deviation
    // of (4/N) sqrt(sum S^4), of which the lags beyond reach hold about M / N. S is that of the null
    // hypothesis, no correlation beyond reach: the transform of the autocorrelation cut at the reach.
    Image within;
    within.width = width, within.height = height, within.channels = 1;
    within.values.assign(plane, 0.0);
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            if (lag_distance(signed_offset(x, width), signed_offset(y, height), options.shape) > reach)
                continue;
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            for (int k = 0; k < basis.channels; k++)
                within.values[i] += autocorrelation.values[size_t(k) * plane + i];
        }
    double fourth_powers = 0;
    for (const std::complex<float> &value : forward_dft(within).values) {
        const double spectrum = double(value.real());
        fourth_powers += spectrum * spectrum * spectrum * spectrum;
    }
    const double noise_deviation =
        4 / double(plane) * double(lags_beyond) / double(plane) * std::sqrt(fourth_powers);
    const bool significant = beyond > 3 * noise_deviation;
    verdict.structure_error = total_energy > 0 ? noise_deviation / total_energy : 0;
    // The strongest correlation beyond reach and its lag (the nearest of equal ones): a periodic
    // pattern's period, or the size of its largest features.
    double strongest = 0;
    int peak_distance = 0;
    for (size_t d = size_t(reach) + 1; d < ring_peak.size(); d++)
        if (ring_peak[d] > strongest) strongest = ring_peak[d], peak_distance = int(d);
    verdict.correlation_beyond_reach = strongest;
    const int fitting = std::min(kMaxRadius, (std::min(width, height) - 1) / 4);
    verdict.largest_fitting_radius = fitting;

    // The noise at the asset's density, as it renders (quantized texton, stored colour transform, read).
    Matrix3 stored_transform{};
    for (size_t i = 0; i < stored_transform.size(); i++)
        stored_transform[i] = double(result.fields.color_transform[i]) / double(DSN_Q24_ONE);
    verdict.impacts = double(result.fields.default_impacts_q16 ? result.fields.default_impacts_q16
                                                               : DSN_IMPACTS_DEFAULT_Q16) /
                      double(DSN_IMPACTS_ONE);
    const NoiseMoments noise =
        noise_moments(result.quantized_texton, stored_transform, options.interpolation, verdict.impacts);
    verdict.noise_skewness = noise.skewness;
    verdict.noise_excess_kurtosis = noise.excess_kurtosis;
    // Skewness shrinks as 1/sqrt(impacts) and excess kurtosis as 1/impacts.
    double needed = verdict.impacts;
    size_t worst = 0;
    double worst_excess = 0;
    for (size_t c = 0; c < noise.skewness.size(); c++) {
        const double skew_share = std::fabs(noise.skewness[c]) / kVerdictNoiseSkewness;
        const double kurtosis_share = std::fabs(noise.excess_kurtosis[c]) / kVerdictNoiseKurtosis;
        needed =
            std::max({needed, verdict.impacts * skew_share * skew_share, verdict.impacts * kurtosis_share});
        if (std::max(skew_share, kurtosis_share) > worst_excess)
            worst_excess = std::max(skew_share, kurtosis_share), worst = c;
    }
    const double largest_impacts = double(DSN_IMPACTS_MAX_Q16) / double(DSN_IMPACTS_ONE);
    const bool sparse = needed > verdict.impacts;
    if (sparse) verdict.suggested_impacts = std::min(largest_impacts, std::ceil(needed));

    // Findings.
    // Only components that carry a visible share of the variance count.
    bool non_gaussian = false;
    {
        for (size_t k = 0; k < verdict.channels.size(); k++) {
            const ChannelMarginal &marginal = verdict.channels[k];
            if (marginal.variance < kVisibleVariance * verdict.channels[0].variance) continue;
            non_gaussian = non_gaussian ||
                           (std::fabs(marginal.skewness) > kVerdictSkewness &&
                            std::fabs(marginal.skewness) > 3 * marginal.skewness_error) ||
                           (std::fabs(marginal.excess_kurtosis) > kVerdictExcessKurtosis &&
                            std::fabs(marginal.excess_kurtosis) > 3 * marginal.kurtosis_error);
        }
    }
    // Shape: on the Gaussianized exemplar (each decorrelated channel through its ranks onto a Gaussian), so
    // that a monotone change of tones, which the tones finding covers, does not count; the visible
    // channel of the smallest total variation ratio. Tones that pass the tones test are Gaussian already:
    // their decorrelated channels stand for the Gaussianized ones (and spare its sort).
    {
        Image gaussian_form;
        if (options.histogram) {
            gaussian_form = result.model.t_u;
        } else if (non_gaussian) {
            gaussian_form =
                gaussian_model(gaussianize(exemplar, histogram_model(exemplar)), options.periodic).t_u;
        } else {
            gaussian_form = model.t_u;
            gaussian_form.channels = basis.channels;
            gaussian_form.values.assign(plane * size_t(basis.channels), 0.0);
            for (int k = 0; k < basis.channels; k++)
                for (int c = 0; c < model.channels; c++) {
                    const double weight = basis.vectors[size_t(c * 3 + k)];
                    for (size_t i = 0; i < plane; i++)
                        gaussian_form.values[size_t(k) * plane + i] +=
                            weight * model.t_u.values[size_t(c) * plane + i];
                }
        }
        for (int k = 0; k < basis.channels; k++) {
            if (basis.variances[size_t(k)] < kVisibleVariance * basis.variances[0]) continue;
            const ShapeSignal signal = shape_signal(gaussian_form, k);
            if (k == 0 || signal.ratio < verdict.shape_ratio)
                verdict.shape_ratio = signal.ratio, verdict.shape_error = signal.error,
                verdict.shape_channel = k;
        }
    }
    const bool shape =
        verdict.shape_ratio < kVerdictShapeRatio && 1 - verdict.shape_ratio > 3 * verdict.shape_error;
    // A correlation of 0.2 of the variance beyond reach is structure; a weaker one counts when the energy
    // it holds there is more than sampling noise explains (large blotches, slow shading, a faint grid).
    const bool structure = verdict.structure_beyond_reach > kVerdictStructureShare &&
                           (verdict.correlation_beyond_reach > kVerdictCorrelation || significant);
    if (structure) {
        // A texton of radius d spans two periods of a pattern of period d: its noise keeps about half of
        // the correlation at lag d.
        const int wanted = std::max(options.radius + 1, peak_distance);
        verdict.suggested_radius = wanted <= fitting ? wanted : 0;
    }

    // The runtime sums about `impacts per pixel` textons at every pixel whatever their size, so a larger
    // radius costs asset bytes (and texture memory), not time per pixel.
    auto radius_cost = [&](int radius) {
        return "asset " + std::to_string(asset_bytes_at(result, radius)) + " bytes instead of " +
               std::to_string(result.asset.size()) + ", about the same runtime cost per pixel";
    };
    if (structure && verdict.suggested_radius > 0) {
        verdict.findings.push_back(VerdictFinding::StructureBeyondRadius);
        verdict.suggestions.push_back(
            "structure reaches beyond the texton (" + format("%.0f%%", 100 * verdict.structure_beyond_reach) +
            " of the autocorrelation energy lies beyond lag " + std::to_string(reach) + "; correlation " +
            format("%.2f", verdict.correlation_beyond_reach) + " at lag " + std::to_string(peak_distance) +
            "): try --radius " + std::to_string(verdict.suggested_radius) + " (" +
            radius_cost(verdict.suggested_radius) + ")");
    } else if (structure) {
        verdict.findings.push_back(VerdictFinding::StructureBeyondGaussian);
        std::string text = "this material has structure a Gaussian model cannot hold here (" +
                           format("%.0f%%", 100 * verdict.structure_beyond_reach) +
                           " of the autocorrelation energy lies beyond the texton's reach, up to lag " +
                           std::to_string(peak_distance) + ", more than the largest radius that fits this " +
                           std::to_string(width) + "x" + std::to_string(height) + " exemplar (" +
                           std::to_string(fitting) + ") can reach)";
        if (fitting > options.radius)
            text +=
                "; --radius " + std::to_string(fitting) + " holds part of it (" + radius_cost(fitting) + ")";
        verdict.suggestions.push_back(text);
    }
    if (non_gaussian && !options.histogram) {
        verdict.findings.push_back(VerdictFinding::NonGaussianMarginal);
        std::string moments;
        for (const ChannelMarginal &marginal : verdict.channels)
            if (marginal.variance >= kVisibleVariance * verdict.channels[0].variance)
                moments += (moments.empty() ? "" : ", ") + format("skewness %.2f", marginal.skewness) +
                           format(" kurtosis %.2f", marginal.excess_kurtosis);
        verdict.suggestions.push_back(
            "the exemplar's tones are far from Gaussian (" + moments +
            " per decorrelated channel): the output keeps its colours' mean and covariance but not its "
            "histogram, so sharp speckles, veins and two-level patterns come out as soft blotches; try "
            "--histogram (a histogram-preserving output: the asset maps the noise back to the exemplar's "
            "own tones, " +
            std::to_string(histogram_table_bytes(result)) +
            " bytes of tables, a table lookup per pixel and channel)");
    }
    if (shape) {
        verdict.findings.push_back(VerdictFinding::ShapeBeyondSpectrum);
        verdict.suggestions.push_back(
            "the exemplar has sharp shapes its spectrum does not hold (" +
            format("total variation %.2f of a random-phase copy's", verdict.shape_ratio) +
            format(", %.0f standard errors below it",
                   (1 - verdict.shape_ratio) / std::max(verdict.shape_error, 1e-12)) +
            ", in decorrelated channel " + std::to_string(verdict.shape_channel + 1) +
            " of its Gaussianized tones: flat regions bounded by sharp edges, as flagstones, facets, stripes "
            "or "
            "discs have): the synthesis keeps the spectrum, not the shapes, which come out as generic grain; "
            "neither a larger radius nor the histogram mapping brings them back");
    }
    if (sparse) {
        verdict.findings.push_back(VerdictFinding::SparseNoise);
        const bool capped = verdict.suggested_impacts < std::ceil(needed);
        verdict.suggestions.push_back(
            format("at %g impacts per pixel the noise is visibly non-Gaussian (", verdict.impacts) +
            format("skewness %.2f", noise.skewness[worst]) +
            format(", excess kurtosis %.2f in output channel ", noise.excess_kurtosis[worst]) +
            std::to_string(worst + 1) + format("; bounds %.2f", kVerdictNoiseSkewness) +
            format(" and %.2f", kVerdictNoiseKurtosis) + "): repeated texton-shaped marks; " +
            format("render with %g impacts per pixel", verdict.suggested_impacts) +
            (capped ? format(" (the most the runtime takes; %g would reach the bounds)", std::ceil(needed))
                    : std::string()) +
            format(" (dsn-render --impacts %g, or dsn_config.impacts_q16)", verdict.suggested_impacts) +
            format(", about %.1fx the runtime cost per pixel", verdict.suggested_impacts / verdict.impacts));
    }
    // Judged on what renders; an RME below the bound is never flagged, whatever the luminance texton's.
    if (verdict.rme_effective > kVerdictModelError) {
        verdict.findings.push_back(VerdictFinding::HighModelError);
        verdict.suggestions.push_back(
            format("the spectrum that renders is far from the exemplar's (RME %.2f as rendered",
                   verdict.rme_effective) +
            format(", %.2f for the texton alone", verdict.rme) + format(", above %.2f", kVerdictModelError) +
            ")" +
            (verdict.rme > verdict.rme_luminance
                 ? format(", and the texton is no closer than the cropped luminance texton (%.2f)",
                          verdict.rme_luminance)
                 : std::string()) +
            (options.radius < fitting ? ": a larger --radius gives the texton more room" : ""));
    }
    const bool fixable_only =
        std::all_of(verdict.findings.begin(), verdict.findings.end(), [](VerdictFinding finding) {
            return finding == VerdictFinding::StructureBeyondRadius || finding == VerdictFinding::SparseNoise;
        });
    if (verdict.findings.empty()) {
        verdict.summary =
            "good: a Gaussian model holds this exemplar (" + format("RME %.2f", verdict.rme_effective) +
            format(" as rendered, %.2f for the texton", verdict.rme) +
            (non_gaussian ? ", non-Gaussian tones kept by the histogram mapping" : ", Gaussian tones") +
            ", structure within the texton's reach" +
            format(", no sharp shapes: total variation %.2f of a random-phase copy's", verdict.shape_ratio) +
            format(", Gaussian noise at %g impacts per pixel)", verdict.impacts);
    } else if (fixable_only) {
        const bool radius = has_finding(verdict, VerdictFinding::StructureBeyondRadius),
                   density = has_finding(verdict, VerdictFinding::SparseNoise);
        verdict.summary = std::string("fair: ") + (radius ? "a larger radius" : "") +
                          (radius && density ? " and " : "") + (density ? "more impacts per pixel" : "") +
                          " would hold more of this exemplar";
    } else {
        verdict.summary = "limited: this exemplar has more than a Gaussian model of this texton holds";
    }
    if (!verdict.findings.empty() && non_gaussian && options.histogram) {
        verdict.summary += " (non-Gaussian tones kept by the histogram mapping)";
    }
    return verdict;
}

const char *verdict_finding_name(VerdictFinding finding) {
    switch (finding) {
    case VerdictFinding::StructureBeyondRadius:
        return "structure_beyond_radius";
    case VerdictFinding::StructureBeyondGaussian:
        return "structure_beyond_gaussian";
    case VerdictFinding::NonGaussianMarginal:
        return "non_gaussian_marginal";
    case VerdictFinding::HighModelError:
        return "high_model_error";
    case VerdictFinding::ShapeBeyondSpectrum:
        return "shape_beyond_spectrum";
    case VerdictFinding::SparseNoise:
        return "sparse_noise";
    }
    return "unknown";
}

} // namespace dsn
