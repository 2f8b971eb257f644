#include "options/option_proto.h"

namespace strata::options {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;

const Message& holder(const v1::RenderOptions& m, const OptionSpec& o) {
  return o.group == Group::experimental ? static_cast<const Message&>(m.experimental()) : m;
}

Message& holder(v1::RenderOptions& m, const OptionSpec& o) {
  return o.group == Group::experimental ? static_cast<Message&>(*m.mutable_experimental()) : m;
}

const FieldDescriptor& field(const OptionSpec& o) {
  const FieldDescriptor* f = proto_field(o);
  if (!f) throw std::logic_error(std::string("option ") + o.name + " has no field in render.proto");
  return *f;
}

}  // namespace

const FieldDescriptor* proto_field(const OptionSpec& o) {
  const auto* d = o.group == Group::experimental ? v1::ExperimentalOptions::descriptor() : v1::RenderOptions::descriptor();
  return d->FindFieldByName(o.name);
}

std::string field_path(const OptionSpec& o, const std::string& prefix) {
  return prefix + (o.group == Group::experimental ? ".experimental." : ".") + o.name;
}

bool has_value(const v1::RenderOptions& m, const OptionSpec& o) {
  if (o.group == Group::experimental && !m.has_experimental()) return false;
  const Message& h = holder(m, o);
  return h.GetReflection()->HasField(h, &field(o));
}

int proto_number(const v1::RenderOptions& m, const OptionSpec& o) {
  const Message& h = holder(m, o);
  return h.GetReflection()->GetEnumValue(h, &field(o));
}

double get_value(const v1::RenderOptions& m, const OptionSpec& o) {
  if (!has_value(m, o)) return default_value(o);
  const Message& h = holder(m, o);
  const auto* r = h.GetReflection();
  const FieldDescriptor& f = field(o);
  switch (f.cpp_type()) {
    case FieldDescriptor::CPPTYPE_UINT32: return double(r->GetUInt32(h, &f));
    case FieldDescriptor::CPPTYPE_FLOAT: return double(r->GetFloat(h, &f));
    case FieldDescriptor::CPPTYPE_BOOL: return r->GetBool(h, &f) ? 1.0 : 0.0;
    case FieldDescriptor::CPPTYPE_ENUM: {
      const Choice* c = find_choice(o, double(r->GetEnumValue(h, &f)), /*by_proto=*/true);
      return c ? double(c->value) : default_value(o);
    }
    default: throw std::logic_error(std::string("option ") + o.name + ": the proto field's type is not an option's");
  }
}

void set_value(v1::RenderOptions& m, const OptionSpec& o, double v) {
  Message& h = holder(m, o);
  const auto* r = h.GetReflection();
  const FieldDescriptor& f = field(o);
  switch (f.cpp_type()) {
    case FieldDescriptor::CPPTYPE_UINT32: r->SetUInt32(&h, &f, uint32_t(v)); break;
    case FieldDescriptor::CPPTYPE_FLOAT: r->SetFloat(&h, &f, float(v)); break;
    case FieldDescriptor::CPPTYPE_BOOL: r->SetBool(&h, &f, v != 0.0); break;
    case FieldDescriptor::CPPTYPE_ENUM: {
      const Choice* c = find_choice(o, v, /*by_proto=*/false);
      if (!c) throw std::logic_error(std::string("option ") + o.name + ": " + std::to_string(v) + " is not a choice");
      r->SetEnumValue(&h, &f, c->proto);
      break;
    }
    default: throw std::logic_error(std::string("option ") + o.name + ": the proto field's type is not an option's");
  }
}

}  // namespace strata::options
