#pragma once
// The first layer of an OGR vector source, as the GDAL plugin's readers (io/gdal_vector.h) open
// it: refusals naming the file, a warning when it holds more layers, fields by name, and the
// number a feature's field holds. Inside the plugin only.

#include <memory>
#include <string>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

namespace radrecon {

/// GDAL's drivers, registered on first use.
void register_ogr_drivers();

/// The first layer of the vector source at `path`, opened read-only.
class OgrLayer {
 public:
  /// UserError naming `path` when there is no such file, GDAL cannot open it as a vector source,
  /// or it has no layer; a warning when it has several (the first is read).
  explicit OgrLayer(const std::string& path);

  OGRLayer& layer() { return *layer_; }
  const std::string& path() const { return path_; }
  OGRFeatureDefn& fields() { return *layer_->GetLayerDefn(); }
  /// "PATH: layer 'NAME', feature FID", for messages.
  std::string where(const OGRFeature& f) const {
    return path_ + ": layer '" + layer_->GetName() + "', feature " + std::to_string(f.GetFID());
  }

  /// The field named `name` (case-insensitive) for option `option`; UserError listing the fields otherwise.
  int field(const std::string& name, const std::string& option);

  bool numeric(int k) {
    const OGRFieldType t = fields().GetFieldDefn(k)->GetType();
    return t == OFTReal || t == OFTInteger || t == OFTInteger64;
  }
  /// A field of text: numbers in it are read (a CSV's columns through a VRT are all text to OGR).
  bool text(int k) { return fields().GetFieldDefn(k)->GetType() == OFTString; }
  bool boolean(int k) { return fields().GetFieldDefn(k)->GetSubType() == OFSTBoolean; }
  std::string name(int k) { return fields().GetFieldDefn(k)->GetNameRef(); }

  /// The finite number in field k of feature f: a numeric field's, or a text field's text read
  /// as a number (as gdal_grid reads it). UserError naming the feature otherwise.
  double number(const OGRFeature& f, int k);

 private:
  std::string path_;
  std::unique_ptr<GDALDataset> data_;
  OGRLayer* layer_ = nullptr;
};

}  // namespace radrecon
