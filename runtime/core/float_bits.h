/* runtime/core/float_bits.h - an IEEE-754 value's bits as an unsigned integer, for the conversions that read
   float inputs with integer operations only (coordinates, surface frames). Internal to libdsn; not
   installed. */
#ifndef DSN_FLOAT_BITS_H
#define DSN_FLOAT_BITS_H

namespace {

/* The object representation of a value as an unsigned integer of the same size (character copies are
   the only aliasing-safe way without memcpy; compilers reduce this to a move). */
template <typename Bits, typename Value>
Bits bits_of(Value value) {
    Bits bits = 0;
    const unsigned char *from = reinterpret_cast<const unsigned char *>(&value);
    unsigned char *to = reinterpret_cast<unsigned char *>(&bits);
    for (unsigned i = 0; i < sizeof(Value); i++) to[i] = from[i];
    return bits;
}

} // namespace

#endif /* DSN_FLOAT_BITS_H */
