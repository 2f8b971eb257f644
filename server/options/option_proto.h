#pragma once
// The option table's rows on the wire: RenderOptions.<name>, or RenderOptions.experimental.<name>
// for the experimental group, read and written through the protobuf descriptor, so that no option
// is named here. Values are those of the table (render/restir/restir_options.h's enums for choices;
// converted from and to the proto enums' numbers by the row's Choice list).
#include <string>

#include "options/option_table.h"
#include "strata/v1/render.pb.h"

namespace strata::options {

namespace v1 = ::strata::v1;

// The row's field; nullptr when the proto has none (a test holds the table and the proto equal).
const google::protobuf::FieldDescriptor* proto_field(const OptionSpec& o);
// "options.spp", "options.experimental.shift": the row's field under `prefix`.
std::string field_path(const OptionSpec& o, const std::string& prefix);

bool has_value(const v1::RenderOptions& m, const OptionSpec& o);
// The value that is set (choices: the RestirOptions value of the proto enum; UNSPECIFIED and
// unknown numbers: the default); the row's default when the field is not set.
double get_value(const v1::RenderOptions& m, const OptionSpec& o);
void set_value(v1::RenderOptions& m, const OptionSpec& o, double v);
// The proto enum number of a choice field as it is set (to report numbers that are no value).
int proto_number(const v1::RenderOptions& m, const OptionSpec& o);

}  // namespace strata::options
