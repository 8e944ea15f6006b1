// SPDX-License-Identifier: GPL-3.0-or-later
// A layer's strategies by keyword (accelerators, mappings, time schedules): the chosen strategy's
// parsed coefficients, type-erased, and the registry entry {name, keys, parse} of each strategy. A
// strategy's parameter struct P provides
//   static constexpr const char* keyword;          // `type:` value and the coefficient block's
//   name using Strategy = <the class>;                  // constructed from P, derived from Product
//   static const std::vector<std::string>& keys(); // the coefficient keys, as documented
//   static P parse(const config::Block& layer);    // reads its block layer.<keyword> (required or
//                                                  // optional, defaults for absent keys); in a
//                                                  // flat layer (time) its keys beside `type`
//   void validate() const;                         // std::runtime_error naming <layer>.<key>
//   std::string echo() const;                      // "{key: value, ...}" for the start-up echo
// and the layer lists strategyType<P, Product>() once in its registry.
// Product provides static constexpr const char* kConfigKey (e.g. "acceleration") for messages.
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fsi::config
{

class Block;

template <class Product> class Strategy
{
public:
    Strategy() = default; // none chosen: validate() and make() throw
    template <class P>
    Strategy(const P& params) // NOLINT: implicit by design
        : type_(P::keyword), model_(std::make_shared<Holder<P>>(params))
    {
    }

    const std::string& type() const { return type_; }
    bool empty() const { return !model_; }
    // Throws std::runtime_error, one line naming the key (<layer>.<key>) and the fix.
    void validate() const
    {
        if (!model_)
            throw std::runtime_error(std::string(Product::kConfigKey) + ".type is not set");
        model_->validate();
    }
    std::unique_ptr<Product> make() const // validates first
    {
        validate();
        return model_->make();
    }
    std::string echo() const { return model_ ? model_->echo() : "{}"; }

    // The coefficients of strategy P, nullptr when another strategy was chosen. Copies do not
    // share them (copy on write).
    template <class P> P* get()
    {
        auto* holder = dynamic_cast<Holder<P>*>(model_.get());
        if (!holder)
            return nullptr;
        if (model_.use_count() > 1)
        {
            model_ = std::make_shared<Holder<P>>(holder->params);
            holder = static_cast<Holder<P>*>(model_.get());
        }
        return &holder->params;
    }
    template <class P> const P* get() const
    {
        const auto* holder = dynamic_cast<const Holder<P>*>(model_.get());
        return holder ? &holder->params : nullptr;
    }

private:
    struct Model
    {
        virtual ~Model() = default;
        virtual void validate() const = 0;
        virtual std::unique_ptr<Product> make() const = 0;
        virtual std::string echo() const = 0;
    };
    template <class P> struct Holder final : Model
    {
        explicit Holder(const P& p) : params(p) {}
        void validate() const override { params.validate(); }
        std::unique_ptr<Product> make() const override
        {
            return std::make_unique<typename P::Strategy>(params);
        }
        std::string echo() const override { return params.echo(); }
        P params;
    };
    std::string type_;
    std::shared_ptr<Model> model_;
};

// One registry entry.
template <class Product> struct StrategyType
{
    std::string name;              // the keyword
    std::vector<std::string> keys; // the keys its coefficient block accepts
    // Reads the strategy's coefficient block from the layer's block (not yet validated).
    std::function<Strategy<Product>(const Block& layer)> parse;
    // The strategy with its default coefficients (required ones unset: validate() says which).
    std::function<Strategy<Product>()> defaults;
};

template <class P, class Product> StrategyType<Product> strategyType()
{
    return {P::keyword, P::keys(), [](const Block& b) { return Strategy<Product>(P::parse(b)); },
            [] { return Strategy<Product>(P{}); }};
}

// The entry called `name` of `types`; throws "<layer>.type 'x' is unknown; use one of a, b".
template <class Product>
const StrategyType<Product>& findStrategyType(const std::vector<StrategyType<Product>>& types,
                                              const std::string& name)
{
    std::string list;
    for (const auto& t : types)
    {
        if (t.name == name)
            return t;
        list += (list.empty() ? "" : ", ") + t.name;
    }
    throw std::runtime_error(std::string(Product::kConfigKey) + ".type '" + name +
                             "' is unknown; use one of " + list);
}

} // namespace fsi::config
