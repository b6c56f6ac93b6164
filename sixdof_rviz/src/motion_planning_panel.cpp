#include "motion_planning_panel.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

namespace sixdof_rviz {
namespace {

QDoubleSpinBox* makeSpin(double min, double max, double step, double value, int decimals) {
  auto* spin = new QDoubleSpinBox;
  spin->setRange(min, max);
  spin->setSingleStep(step);
  spin->setDecimals(decimals);
  spin->setValue(value);
  return spin;
}

}  // namespace

MotionPlanningPanel::MotionPlanningPanel(QWidget* parent) : rviz::Panel(parent) {
  const PlanningSettings defaults;
  group_combo_ = new QComboBox;
  goal_source_combo_ = new QComboBox;
  goal_source_combo_->addItem("Named state", static_cast<int>(GoalSource::kNamedState));
  goal_source_combo_->addItem("Goal marker", static_cast<int>(GoalSource::kGoalMarker));
  goal_source_combo_->addItem("Random valid state", static_cast<int>(GoalSource::kRandomValid));
  named_state_combo_ = new QComboBox;
  planner_combo_ = new QComboBox;
  planner_combo_->setEditable(true);
  planner_combo_->addItems({"RRTConnect", "RRTstar", "PRM", "BiTRRT", "KPIECE1"});
  planning_time_spin_ = makeSpin(0.1, 300.0, 0.5, defaults.planning_time, 1);
  attempts_spin_ = new QSpinBox;
  attempts_spin_->setRange(1, 1000);
  attempts_spin_->setValue(defaults.attempts);
  velocity_spin_ = makeSpin(0.01, 1.0, 0.05, defaults.velocity_scaling, 2);
  acceleration_spin_ = makeSpin(0.01, 1.0, 0.05, defaults.acceleration_scaling, 2);

  auto* form = new QFormLayout;
  form->addRow("Planning group", group_combo_);
  form->addRow("Goal", goal_source_combo_);
  form->addRow("Named state", named_state_combo_);
  form->addRow("Planner", planner_combo_);
  form->addRow("Planning time [s]", planning_time_spin_);
  form->addRow("Attempts", attempts_spin_);
  form->addRow("Velocity scaling", velocity_spin_);
  form->addRow("Acceleration scaling", acceleration_spin_);

  plan_button_ = new QPushButton("Plan");
  execute_button_ = new QPushButton("Execute");
  plan_execute_button_ = new QPushButton("Plan && Execute");
  stop_button_ = new QPushButton("Stop");
  auto* buttons = new QHBoxLayout;
  for (QPushButton* button : {plan_button_, execute_button_, plan_execute_button_, stop_button_}) {
    buttons->addWidget(button);
  }
  status_label_ = new QLabel("Not initialized");
  status_label_->setWordWrap(true);
  status_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  auto* layout = new QVBoxLayout;
  layout->addLayout(form);
  layout->addLayout(buttons);
  layout->addWidget(status_label_);
  layout->addStretch();
  setLayout(layout);

  connect(group_combo_, SIGNAL(currentIndexChanged(int)), this, SLOT(groupChanged()));
  connect(goal_source_combo_, SIGNAL(currentIndexChanged(int)), this, SLOT(goalSourceChanged()));
  connect(plan_button_, SIGNAL(clicked()), this, SLOT(planClicked()));
  connect(execute_button_, SIGNAL(clicked()), this, SLOT(executeClicked()));
  connect(plan_execute_button_, SIGNAL(clicked()), this, SLOT(planAndExecuteClicked()));
  connect(stop_button_, SIGNAL(clicked()), this, SLOT(stopClicked()));
  for (QPushButton* button : {plan_button_, execute_button_, plan_execute_button_, stop_button_}) {
    button->setEnabled(false);
  }
}

MotionPlanningPanel::~MotionPlanningPanel() = default;

void MotionPlanningPanel::onInitialize() {
  ros::NodeHandle nh;
  std::string urdf_xml;
  std::string srdf_xml;
  if (!nh.getParam("robot_description", urdf_xml) || !nh.getParam("robot_description_semantic", srdf_xml)) {
    initFailed("parameters robot_description and robot_description_semantic must be set");
    return;
  }
  try {
    model_ = std::make_shared<SemanticModel>(urdf_xml, srdf_xml);
  } catch (const std::invalid_argument& e) {
    initFailed(e.what());
    return;
  }
  logic_ = std::make_unique<PlanningPanelLogic>(nh, model_, [this](const PanelStatus& s) { showStatus(s); });
  group_combo_->blockSignals(true);
  for (const auto& group : model_->groups()) group_combo_->addItem(QString::fromStdString(group.name));
  group_combo_->blockSignals(false);
  applySavedChoices();
  for (QPushButton* button : {plan_button_, execute_button_, plan_execute_button_, stop_button_}) {
    button->setEnabled(true);
  }
  showStatus({PanelStatus::Level::kInfo, "Ready"});
}

void MotionPlanningPanel::initFailed(const std::string& text) {
  showStatus({PanelStatus::Level::kError, text});
  ROS_ERROR_STREAM("MotionPlanningPanel: " << text);
}

void MotionPlanningPanel::applySavedChoices() {
  if (!model_) return;
  int group = group_combo_->findText(saved_group_);
  group_combo_->blockSignals(true);
  group_combo_->setCurrentIndex(group >= 0 ? group : 0);
  group_combo_->blockSignals(false);
  groupChanged();
  int named = named_state_combo_->findText(saved_named_state_);
  if (named >= 0) named_state_combo_->setCurrentIndex(named);
}

void MotionPlanningPanel::groupChanged() {
  named_state_combo_->clear();
  if (!model_) return;
  for (const auto& name : model_->namedStates(group_combo_->currentText().toStdString())) {
    named_state_combo_->addItem(QString::fromStdString(name));
  }
  goalSourceChanged();
}

void MotionPlanningPanel::goalSourceChanged() {
  named_state_combo_->setEnabled(goalSpec().source == GoalSource::kNamedState);
}

PlanningSettings MotionPlanningPanel::settings() const {
  PlanningSettings s;
  s.group = group_combo_->currentText().toStdString();
  s.planner_id = planner_combo_->currentText().trimmed().toStdString();
  s.planning_time = planning_time_spin_->value();
  s.attempts = attempts_spin_->value();
  s.velocity_scaling = velocity_spin_->value();
  s.acceleration_scaling = acceleration_spin_->value();
  return s;
}

GoalSpec MotionPlanningPanel::goalSpec() const {
  GoalSpec spec;
  spec.source = static_cast<GoalSource>(goal_source_combo_->currentData().toInt());
  spec.named_state = named_state_combo_->currentText().toStdString();
  return spec;
}

void MotionPlanningPanel::showStatus(const PanelStatus& status) {
  const char* color = status.level == PanelStatus::Level::kError ? "#c00000"
                      : status.level == PanelStatus::Level::kOk  ? "#007000"
                                                                 : "#000000";
  status_label_->setStyleSheet(QString("QLabel { color: %1; }").arg(color));
  status_label_->setText(QString::fromStdString(status.text));
}

void MotionPlanningPanel::planClicked() {
  if (logic_) logic_->plan(settings(), goalSpec());
}

void MotionPlanningPanel::executeClicked() {
  if (logic_) logic_->execute();
}

void MotionPlanningPanel::planAndExecuteClicked() {
  if (logic_) logic_->planAndExecute(settings(), goalSpec());
}

void MotionPlanningPanel::stopClicked() {
  if (logic_) logic_->stop();
}

void MotionPlanningPanel::save(rviz::Config config) const {
  rviz::Panel::save(config);
  config.mapSetValue("Group", group_combo_->currentText());
  config.mapSetValue("GoalSource", goal_source_combo_->currentIndex());
  config.mapSetValue("NamedState", named_state_combo_->currentText());
  config.mapSetValue("Planner", planner_combo_->currentText());
  config.mapSetValue("PlanningTime", planning_time_spin_->value());
  config.mapSetValue("Attempts", attempts_spin_->value());
  config.mapSetValue("VelocityScaling", velocity_spin_->value());
  config.mapSetValue("AccelerationScaling", acceleration_spin_->value());
}

void MotionPlanningPanel::load(const rviz::Config& config) {
  rviz::Panel::load(config);
  QString text;
  int number = 0;
  float value = 0.0f;
  // The group and named-state lists come from the robot model, which may not be loaded yet.
  if (config.mapGetString("Group", &text)) saved_group_ = text;
  if (config.mapGetString("NamedState", &text)) saved_named_state_ = text;
  applySavedChoices();
  if (config.mapGetInt("GoalSource", &number)) goal_source_combo_->setCurrentIndex(number);
  if (config.mapGetString("Planner", &text)) planner_combo_->setCurrentText(text);
  if (config.mapGetFloat("PlanningTime", &value)) planning_time_spin_->setValue(value);
  if (config.mapGetInt("Attempts", &number)) attempts_spin_->setValue(number);
  if (config.mapGetFloat("VelocityScaling", &value)) velocity_spin_->setValue(value);
  if (config.mapGetFloat("AccelerationScaling", &value)) acceleration_spin_->setValue(value);
}

}  // namespace sixdof_rviz

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(sixdof_rviz::MotionPlanningPanel, rviz::Panel)
